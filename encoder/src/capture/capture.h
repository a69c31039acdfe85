// Capture: a multi-view video as every training stage sees it, whatever layout it was
// loaded from: cameras per frame (intrinsics at the loaded resolution, world-to-camera in
// OpenCV axes, see sdk/src/render/camera.h), images decoded on demand, an initial point
// cloud and the held-out test camera.
#ifndef M4D_ENCODER_CAPTURE_CAPTURE_H_
#define M4D_ENCODER_CAPTURE_CAPTURE_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

// Decodes one view's image. Implementations may keep state (open video decoders) but must
// give the same pixels for the same (frame, camera) whatever the order of requests.
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // RGB (3 channels) at the capture's resolution into *rgb (its storage is reused).
  virtual Status Load(int frame, int camera, Image* rgb) = 0;
};

struct Capture {
  std::string layout;  // the layout it was read from, e.g. "n3dv"
  int frame_count = 0;
  std::vector<std::string> camera_names;     // one per camera
  std::vector<std::vector<Camera>> cameras;  // [frame][camera]; a fixed rig repeats its row
  // Held out from training, in index order. A loader sets the layout's own held-out cameras
  // (Dynamic3DGaussians' test_meta.json); CaptureOptions::test_camera may replace them.
  std::vector<int> test_cameras;
  // Frames per second as fps_num / fps_den when the layout records it (N3DV: 30); 0: unknown.
  uint32_t fps_num = 0, fps_den = 1;
  PointCloud initial_points;  // may be empty: initialise in the cameras' common view
  std::unique_ptr<FrameSource> frames;
  std::vector<std::string> notes;  // what the loader changed, e.g. undistorted cameras

  int camera_count() const { return static_cast<int>(camera_names.size()); }
  const Camera& camera(int frame, int index) const { return cameras[frame][index]; }
  // The cameras trained on: every camera but the test cameras, in index order.
  std::vector<int> TrainCameras() const;
  bool IsTestCamera(int index) const;
  // The first test camera (the one players and single-view reports use); -1: none.
  int FirstTestCamera() const { return test_cameras.empty() ? -1 : test_cameras[0]; }
  // frames->Load with range checks (M4D_ERR_INVALID_ARG for a bad index).
  Status LoadImage(int frame, int camera, Image* rgb) const;
};

}  // namespace m4d

#endif  // M4D_ENCODER_CAPTURE_CAPTURE_H_
