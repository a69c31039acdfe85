#include "encoder/src/dataset/colmap_loader.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "encoder/src/dataset/file_listing.h"
#include "encoder/src/dataset/image_file_source.h"
#include "encoder/src/dataset/undistorting_frame_source.h"

namespace m4d {

std::string FindColmapModelDir(const std::string& dir) {
  for (const std::string& candidate : {dir + "/sparse/0", dir + "/sparse", dir}) {
    if (IsColmapModelDir(candidate)) return candidate;
  }
  return "";
}

Status ColmapImageCamera(const ColmapCamera& intrinsics, const ColmapImage& image, Camera* camera,
                         LensDistortion* distortion) {
  double fx, fy, cx, cy;
  M4D_RETURN_IF_ERROR(ColmapIntrinsics(intrinsics, &fx, &fy, &cx, &cy, distortion));
  if (intrinsics.width < 1 || intrinsics.height < 1 || intrinsics.width > kMaxImageSide ||
      intrinsics.height > kMaxImageSide) {
    return Status(M4D_ERR_INVALID_ARG, "colmap: camera size out of range");
  }
  camera->width = static_cast<int>(intrinsics.width);
  camera->height = static_cast<int>(intrinsics.height);
  camera->fx = static_cast<float>(fx);
  camera->fy = static_cast<float>(fy);
  camera->cx = static_cast<float>(cx);
  camera->cy = static_cast<float>(cy);
  // COLMAP's unit quaternion (w, x, y, z) is the world-to-camera rotation; normalising
  // absorbs the rounding of text files.
  const double* q = image.qvec;
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(norm > 1e-12)) return Status(M4D_ERR_INVALID_ARG, "colmap: zero quaternion");
  const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                       2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                       2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  for (int i = 0; i < 9; ++i) camera->rotation[i] = static_cast<float>(r[i]);
  for (int i = 0; i < 3; ++i) camera->translation[i] = static_cast<float>(image.tvec[i]);
  return Status::Ok();
}

Status LoadColmap(const std::string& dir, const CaptureOptions& options, Capture* capture) {
  M4D_RETURN_IF_ERROR(CheckCaptureOptions(options));
  *capture = Capture();
  capture->layout = "colmap";
  const std::string model_dir = FindColmapModelDir(dir);
  if (model_dir.empty()) return Status(M4D_ERR_INVALID_ARG, "colmap: no model in '" + dir + "'");
  ColmapModel model;
  M4D_RETURN_IF_ERROR(ReadColmapModel(model_dir, options.initial_points.empty(), &model));
  if (model.images.empty()) return Status(M4D_ERR_INVALID_ARG, "colmap: no registered images");
  std::unordered_map<uint32_t, const ColmapCamera*> cameras;
  for (const ColmapCamera& camera : model.cameras) cameras[camera.id] = &camera;

  std::sort(
      model.images.begin(), model.images.end(),
      [](const ColmapImage& a, const ColmapImage& b) { return FrameNameLess(a.name, b.name); });
  capture->frame_count = 1;
  capture->cameras.resize(1);
  std::vector<std::vector<std::string>> paths(1);
  std::vector<std::vector<LensDistortion>> distortions(1);
  for (size_t i = 0; i < model.images.size(); ++i) {
    const ColmapImage& image = model.images[i];
    if (i > 0 && image.name == model.images[i - 1].name) {
      return Status(M4D_ERR_INVALID_ARG, "colmap: image '" + image.name + "' registered twice");
    }
    const auto found = cameras.find(image.camera_id);
    if (found == cameras.end()) {
      return Status(M4D_ERR_INVALID_ARG, "colmap: image '" + image.name + "' has no camera");
    }
    Camera camera;
    LensDistortion distortion;
    M4D_RETURN_IF_ERROR(ColmapImageCamera(*found->second, image, &camera, &distortion));
    capture->camera_names.push_back(image.name);
    capture->cameras[0].push_back(camera);
    distortions[0].push_back(distortion);
    paths[0].push_back(dir + "/images/" + image.name);
  }
  capture->initial_points = std::move(model.points);
  capture->frames = std::make_unique<ImageFileSource>(std::move(paths), capture->cameras);
  M4D_RETURN_IF_ERROR(UndistortCapture(distortions, capture));
  return ApplyCaptureOptions(options, capture);
}

}  // namespace m4d
