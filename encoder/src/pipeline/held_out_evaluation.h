// The quality of a decoded frame on the capture's held-out cameras (which no stage trains on),
// what the frame reports say of the stream.
#ifndef M4D_ENCODER_PIPELINE_HELD_OUT_EVALUATION_H_
#define M4D_ENCODER_PIPELINE_HELD_OUT_EVALUATION_H_

#include <functional>

#include "encoder/src/capture/capture.h"
#include "encoder/src/image/image.h"
#include "encoder/src/pipeline/frame_report.h"
#include "encoder/src/raster/render_settings.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// The held-out camera's image of a frame and the render of its decoded Gaussians.
using HeldOutViewCallback = std::function<void(int frame, const Image& truth, const Image& render)>;

// Sets report's Gaussian counts and, when the capture has held-out cameras, their mean PSNR and
// SSIM of the decoded frame (static_set with dynamic_set); passes the first one's image and
// render to held_out_view (may be empty).
Status EvaluateHeldOut(const Capture& capture, int frame, const GaussianSet& static_set,
                       const GaussianSet& dynamic_set, const RenderSettings& settings,
                       const HeldOutViewCallback& held_out_view, FrameReport* report);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_HELD_OUT_EVALUATION_H_
