// COLMAP sparse models (cameras, images, points3D) as COLMAP writes them, in its binary
// (.bin) or text (.txt) form, and the intrinsics and lens distortion of its camera models.
#ifndef M4D_ENCODER_DATASET_COLMAP_MODEL_H_
#define M4D_ENCODER_DATASET_COLMAP_MODEL_H_

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/dataset/lens_distortion.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Largest COLMAP model file read: 2 GiB.
constexpr size_t kMaxColmapFileBytes = size_t{1} << 31;

struct ColmapCamera {
  uint32_t id = 0;
  int model_id = 0;  // COLMAP's numbering, see ColmapModelName
  uint64_t width = 0;
  uint64_t height = 0;
  std::vector<double> params;  // as many as the model has
};

struct ColmapImage {
  uint32_t id = 0;
  double qvec[4] = {1, 0, 0, 0};  // world-to-camera rotation, w x y z
  double tvec[3] = {0, 0, 0};     // world-to-camera translation
  uint32_t camera_id = 0;
  std::string name;  // path relative to the image directory
};

struct ColmapModel {
  std::vector<ColmapCamera> cameras;
  std::vector<ColmapImage> images;
  PointCloud points;
};

// The model's name ("PINHOLE", ...) and parameter count, or nullptr / -1 for an unknown id.
const char* ColmapModelName(int model_id);
int ColmapModelParamCount(int model_id);
// The id of a model name, or -1.
int ColmapModelId(const std::string& name);

// Intrinsics of SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, OPENCV_FISHEYE and
// FULL_OPENCV cameras: focal lengths, principal point and lens distortion (model kNone for
// the pinhole models). M4D_ERR_UNSUPPORTED naming any other model.
Status ColmapIntrinsics(const ColmapCamera& camera, double* fx, double* fy, double* cx, double* cy,
                        LensDistortion* distortion);

// Reads cameras, images and (when with_points) points3D from `dir`, each from its .bin file
// if there is one, else from its .txt file.
Status ReadColmapModel(const std::string& dir, bool with_points, ColmapModel* model);

// Reads only points3D.bin or points3D.txt from `dir`.
Status ReadColmapPoints(const std::string& dir, PointCloud* points);

// Whether `dir` holds a COLMAP model (a cameras.bin or cameras.txt).
bool IsColmapModelDir(const std::string& dir);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_COLMAP_MODEL_H_
