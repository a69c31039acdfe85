// Parsers for COLMAP's text model files (cameras.txt, images.txt, points3D.txt): '#'
// comments, one record per line (two for an image: its pose line, then its 2D points line,
// which may be empty).
#ifndef M4D_ENCODER_DATASET_COLMAP_TEXT_H_
#define M4D_ENCODER_DATASET_COLMAP_TEXT_H_

#include <string>
#include <vector>

#include "encoder/src/dataset/colmap_model.h"
#include "sdk/src/common/status.h"

namespace m4d {

// M4D_ERR_BITSTREAM for a line that does not parse (quoted with its line number) or an
// unknown camera model.
Status ParseColmapCamerasText(const std::string& text, std::vector<ColmapCamera>* cameras);
Status ParseColmapImagesText(const std::string& text, std::vector<ColmapImage>* images);
Status ParseColmapPointsText(const std::string& text, PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_COLMAP_TEXT_H_
