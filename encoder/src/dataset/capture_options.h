// CaptureOptions: the choices every capture loader applies the same way once it has read a
// layout at full resolution: the frame window, integer downscaling, the held-out test
// camera and an optional replacement of the initial points.
#ifndef M4D_ENCODER_DATASET_CAPTURE_OPTIONS_H_
#define M4D_ENCODER_DATASET_CAPTURE_OPTIONS_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "sdk/src/common/status.h"

namespace m4d {

// CaptureOptions::test_camera's default: the layout's own held-out cameras when it has them
// (Dynamic3DGaussians' test_meta.json), else camera 0 (the N3DV convention) when there are
// at least two cameras.
constexpr int kLayoutTestCameras = -2;

struct CaptureOptions {
  // Held out from training: kLayoutTestCameras, -1 (none) or one camera index (then the
  // layout's own held-out cameras train like the others).
  int test_camera = kLayoutTestCameras;
  // Integer factor: images are area-averaged to (width / downscale, height / downscale)
  // (rounded down) and intrinsics scaled by the same ratio per axis, exactly 1 / downscale
  // when the factor divides the size.
  int downscale = 1;
  int first_frame = 0;
  int max_frames = 0;  // 0: every frame from first_frame on
  // Initial points replacing the layout's own: a COLMAP sparse model directory (only its
  // points3D is read) or a PLY point cloud, in the capture's world frame.
  std::string initial_points;
};

// M4D_ERR_INVALID_ARG for negative values, downscale outside 1..64 or test_camera < -2.
Status CheckCaptureOptions(const CaptureOptions& options);

// Narrows a full-resolution capture to the frame window, downscales its cameras and wraps
// its frame source to match, sets the test cameras, replaces the initial points if asked,
// mirrors a left-handed world (world_handedness.h) and validates every camera. M4D_ERR_INVALID_ARG
// when the window starts past the last frame, the test camera does not exist or a camera is
// degenerate.
Status ApplyCaptureOptions(const CaptureOptions& options, Capture* capture);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_CAPTURE_OPTIONS_H_
