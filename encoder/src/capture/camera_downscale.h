// A camera's intrinsics at a lower resolution, matching images area-averaged by the same
// integer factor (area_resize.h).
#ifndef M4D_ENCODER_CAPTURE_CAMERA_DOWNSCALE_H_
#define M4D_ENCODER_CAPTURE_CAMERA_DOWNSCALE_H_

#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

// The camera of (width / factor, height / factor) pixels (rounded down): focal lengths and
// principal point scaled by exactly that ratio per axis. M4D_ERR_INVALID_ARG when no pixel
// would be left.
Status DownscaleCamera(int factor, Camera* camera);

}  // namespace m4d

#endif  // M4D_ENCODER_CAPTURE_CAMERA_DOWNSCALE_H_
