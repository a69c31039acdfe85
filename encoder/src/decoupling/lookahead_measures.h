// What the lookahead fine-tuning (paper section 4.1) tells about each Gaussian of a keyframe,
// the inputs of ClassifyDynamic (motion_classification.h):
//  - delta_i = |d_i| / z_i: d_i the displacement in pixels of its projected centre between the
//    keyframe model and the model fine-tuned on frame t1, z_i its depth in the keyframe model,
//    averaged over the cameras that see its centre in front of the near plane and inside the
//    image. Pixels and depth are those of the capture as loaded.
//  - |delta s_i|: the Euclidean norm of the change of its log scales (a relative change,
//    independent of the scene's units).
//  - E_L1_i (paper eq. e_l1): its blend-weighted mean absolute error against frame t1 over all
//    training views, from the sums RenderForward accumulates (blend_weight, error_weight).
#ifndef M4D_ENCODER_DECOUPLING_LOOKAHEAD_MEASURES_H_
#define M4D_ENCODER_DECOUPLING_LOOKAHEAD_MEASURES_H_

#include <cstddef>
#include <vector>

#include "encoder/src/decoupling/motion_classification.h"
#include "sdk/src/render/camera.h"

namespace m4d {

struct LookaheadInput {
  size_t count = 0;
  const float* positions_before = nullptr;   // 3 per Gaussian
  const float* positions_after = nullptr;    // 3 per Gaussian
  const float* log_scales_before = nullptr;  // 3 per Gaussian
  const float* log_scales_after = nullptr;   // 3 per Gaussian
  // Summed over the training views of frame t1, per Gaussian: sum of alpha T, and of
  // alpha T times the pixel's mean absolute error.
  const float* blend_weight = nullptr;
  const float* error_weight = nullptr;
};

LookaheadMeasures MeasureLookahead(const std::vector<Camera>& cameras, const LookaheadInput& input);

}  // namespace m4d

#endif  // M4D_ENCODER_DECOUPLING_LOOKAHEAD_MEASURES_H_
