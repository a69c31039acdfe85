// The thinnest Gaussian axis worth coding. The renderer adds 0.3 px^2 to every projected
// covariance (projection_constants.h), so an axis far below a pixel draws as that dilation
// alone: a keyframe's log scales reach e^-16 (default scene) although the views cannot tell
// e^-7 from it, and a range that spans them spends its few levels on what no view shows.
#ifndef M4D_ENCODER_LAYERS_LOG_SCALE_FLOOR_H_
#define M4D_ENCODER_LAYERS_LOG_SCALE_FLOOR_H_

#include <vector>

#include "dataset/capture.h"
#include "render/camera.h"

namespace m4d {

// An axis this many pixels wide widens the 0.3 px^2 dilation's splat by under 2 %. Measured on
// the default scene's keyframe at r1's bits: floors at 0.05, 0.13 and 0.2 px render within
// 0.05 dB of each other, 0.7 dB above no floor.
constexpr float kInvisibleAxisPixels = 0.1f;

// log(kInvisibleAxisPixels x d / f), f the largest focal length in pixels and d the scene's
// depth: the median depth, along the optical axes, of the point nearest all of them (where
// the cameras look), or where the axes are near parallel the median distance of the centres
// from their mean (less than the scene's depth: a lower floor). -inf (no floor) for fewer
// than two cameras or when the centres coincide.
float LogScaleFloor(const std::vector<Camera>& cameras);

// The floor of the capture's training cameras at `frame`, so that every stage that quantizes
// a keyframe of that frame (training, the encoder, m4d train's report) uses the same range.
float TrainingLogScaleFloor(const Capture& capture, int frame);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_LOG_SCALE_FLOOR_H_
