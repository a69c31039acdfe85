// Whether two Gaussian sets hold the same Gaussians, value for value, in the same order.
#ifndef M4D_ENCODER_LAYERS_SAME_GAUSSIAN_SET_H_
#define M4D_ENCODER_LAYERS_SAME_GAUSSIAN_SET_H_

#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

inline bool SameGaussianSet(const GaussianSet& a, const GaussianSet& b) {
  return a.sh_degree == b.sh_degree && a.positions == b.positions && a.log_scales == b.log_scales &&
         a.rotations == b.rotations && a.opacity_logits == b.opacity_logits && a.sh == b.sh;
}

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_SAME_GAUSSIAN_SET_H_
