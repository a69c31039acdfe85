#include "encoder/src/dataset/capture_options.h"

#include <utility>

#include "encoder/src/capture/camera_downscale.h"
#include "encoder/src/dataset/initial_points.h"
#include "encoder/src/dataset/world_handedness.h"
#include "encoder/src/image/area_resize.h"

namespace m4d {
namespace {

// Serves frame f of the window as frame first_frame + f of the full capture, area-averaged
// by the downscale factor.
class WindowedFrameSource : public FrameSource {
 public:
  WindowedFrameSource(std::unique_ptr<FrameSource> full, int first_frame, int downscale)
      : full_(std::move(full)), first_frame_(first_frame), downscale_(downscale) {}

  Status Load(int frame, int camera, Image* rgb) override {
    if (downscale_ == 1) return full_->Load(first_frame_ + frame, camera, rgb);
    Image image;
    M4D_RETURN_IF_ERROR(full_->Load(first_frame_ + frame, camera, &image));
    return ResizeArea(image, image.width / downscale_, image.height / downscale_, rgb);
  }

 private:
  std::unique_ptr<FrameSource> full_;
  int first_frame_;
  int downscale_;
};

void SelectTestCameras(int test_camera, Capture* capture) {
  if (test_camera >= 0) {
    capture->test_cameras = {test_camera};
  } else if (test_camera == -1) {
    capture->test_cameras.clear();
  } else if (capture->test_cameras.empty() && capture->camera_count() > 1) {
    capture->test_cameras = {0};
  }
}

}  // namespace

Status CheckCaptureOptions(const CaptureOptions& options) {
  if (options.downscale < 1 || options.downscale > 64) {
    return Status(M4D_ERR_INVALID_ARG, "capture: downscale must be 1..64");
  }
  if (options.first_frame < 0 || options.max_frames < 0 ||
      options.test_camera < kLayoutTestCameras) {
    return Status(M4D_ERR_INVALID_ARG,
                  "capture: first_frame and max_frames must be >= 0, test_camera >= -1");
  }
  return Status::Ok();
}

Status ApplyCaptureOptions(const CaptureOptions& options, Capture* capture) {
  M4D_RETURN_IF_ERROR(CheckCaptureOptions(options));
  if (options.first_frame >= capture->frame_count) {
    return Status(M4D_ERR_INVALID_ARG, "capture: first_frame " +
                                           std::to_string(options.first_frame) + " but only " +
                                           std::to_string(capture->frame_count) + " frames");
  }
  if (options.test_camera >= capture->camera_count()) {
    return Status(M4D_ERR_INVALID_ARG, "capture: test camera " +
                                           std::to_string(options.test_camera) + " but only " +
                                           std::to_string(capture->camera_count()) + " cameras");
  }
  int count = capture->frame_count - options.first_frame;
  if (options.max_frames > 0 && options.max_frames < count) count = options.max_frames;
  capture->cameras.erase(capture->cameras.begin(), capture->cameras.begin() + options.first_frame);
  capture->cameras.resize(count);
  capture->frame_count = count;
  if (!options.initial_points.empty()) {
    M4D_RETURN_IF_ERROR(LoadInitialPoints(options.initial_points, &capture->initial_points));
  }
  M4D_RETURN_IF_ERROR(MakeWorldRightHanded(capture));
  for (std::vector<Camera>& row : capture->cameras) {
    for (Camera& camera : row) {
      if (options.downscale > 1) M4D_RETURN_IF_ERROR(DownscaleCamera(options.downscale, &camera));
      const Status valid = ValidateCamera(camera);
      if (!valid.ok()) {
        return Status(M4D_ERR_INVALID_ARG, capture->layout + ": " + valid.message());
      }
    }
  }
  if (options.first_frame > 0 || options.downscale > 1) {
    capture->frames = std::make_unique<WindowedFrameSource>(std::move(capture->frames),
                                                            options.first_frame, options.downscale);
  }
  SelectTestCameras(options.test_camera, capture);
  return Status::Ok();
}

}  // namespace m4d
