// The initial compensated Gaussians of an inter frame (paper section 3.4), before their
// optimisation (compensation_training.h):
//  - replication: Gaussians of the moved dynamic set whose centres sit where the image
//    gradient is large. We measure it with the view-space positional gradient of L_color
//    averaged over the training views (the statistic 3DGS densifies on); the paper's
//    tau_g = 1e-4 is on that scale. On the default scene it replicates about half the dynamic
//    set every frame, so our default is 5e-4. Likewise tau_mu = 0.08 and tau_R = pi / 4 split
//    a quarter of the default scene's dynamic set every frame (its units are metres and its
//    figure moves several centimetres per frame); our defaults are 0.25 and pi / 2.
//  - splitting: a Gaussian whose predicted translation exceeds tau_mu or whose rotation
//    increment turns by more than tau_R is replaced by two children drawn from
//    N(mu, 2 Sigma) with scales divided by 100.
#ifndef M4D_ENCODER_COMPENSATION_COMPENSATION_CANDIDATES_H_
#define M4D_ENCODER_COMPENSATION_COMPENSATION_CANDIDATES_H_

#include <cstdint>
#include <vector>

#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

struct CompensationThresholds {
  float gradient = 5e-4f;       // tau_g
  float translation = 0.25f;    // tau_mu, scene units
  float rotation = 1.5707964f;  // tau_R, radians
  float split_scale_divisor = 100.0f;
};

struct CompensationCandidates {
  GaussianSet added;             // replicas, then split children
  std::vector<uint8_t> removed;  // per Gaussian of the moved set: 1 = replaced by its children
  size_t replicated = 0;
  size_t split = 0;  // parents split (2 children each)
};

// moved: the dynamic set after this frame's motion; viewspace_gradient: per Gaussian of it,
// the mean view-space gradient norm; motion: per Gaussian, the 7 motion outputs (translation,
// quaternion increment), zero for Gaussians the motion left alone. Deterministic given seed.
CompensationCandidates ProposeCompensation(const GaussianSet& moved,
                                           const std::vector<float>& viewspace_gradient,
                                           const std::vector<float>& motion,
                                           const CompensationThresholds& thresholds, uint32_t seed);

// The angle in radians of the rotation by quaternion increment (1 + o3, o4, o5, o6).
float IncrementAngle(const float* o);

}  // namespace m4d

#endif  // M4D_ENCODER_COMPENSATION_COMPENSATION_CANDIDATES_H_
