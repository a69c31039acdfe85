// Loader for COLMAP reconstructions as a static capture of one frame: every registered
// image is a camera (named by its image name, cameras in sorted name order), images come
// from <dir>/images/<name>, points3D gives the initial points. The model is read from
// <dir>/sparse/0, <dir>/sparse or <dir> itself, binary or text. Cameras with lens
// distortion (radial, OpenCV, full OpenCV, OpenCV fisheye) are undistorted to pinhole
// cameras of the same image size, images included (noted in Capture::notes).
#ifndef M4D_ENCODER_DATASET_COLMAP_LOADER_H_
#define M4D_ENCODER_DATASET_COLMAP_LOADER_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/capture_options.h"
#include "encoder/src/dataset/colmap_model.h"
#include "sdk/src/common/status.h"

namespace m4d {

Status LoadColmap(const std::string& dir, const CaptureOptions& options, Capture* capture);

// The model directory under `dir` (see above), or "" when there is none.
std::string FindColmapModelDir(const std::string& dir);

// The camera of a registered image as COLMAP calibrated it: intrinsics and *distortion of
// its COLMAP camera, pose from its quaternion and translation.
Status ColmapImageCamera(const ColmapCamera& intrinsics, const ColmapImage& image, Camera* camera,
                         LensDistortion* distortion);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_COLMAP_LOADER_H_
