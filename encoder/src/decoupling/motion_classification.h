// Classification of a keyframe's Gaussians into static and dynamic (paper section 3.2, the
// "initial classification, error refinement, clustering smoothing" of section 4.1), given the
// per-Gaussian measures the lookahead fine-tuning produced (lookahead_measures.h).
#ifndef M4D_ENCODER_DECOUPLING_MOTION_CLASSIFICATION_H_
#define M4D_ENCODER_DECOUPLING_MOTION_CLASSIFICATION_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace m4d {

// The paper's thresholds (section 5.1) in our units; see lookahead_measures.h for the units.
struct DecouplingThresholds {
  float displacement = 4.5f;  // tau_delta, on delta_i = |d_i| / z_i
  float scale_change = 0.1f;  // tau_s, on |change of log scales|
  float error = 0.02f;        // tau_E, on E_L1 (mean absolute error per channel, in [0, 1])
  int neighbours = 5;         // K of the majority vote
};

// Per Gaussian, what the lookahead measured.
struct LookaheadMeasures {
  std::vector<float> displacement;  // delta_i
  std::vector<float> scale_change;  // |delta s_i|
  std::vector<float> error;         // E_L1_i; NaN where the Gaussian covered no pixel
  size_t size() const { return displacement.size(); }
};

// 1 = dynamic, per Gaussian. `neighbours` holds, for each Gaussian, the indices of its
// thresholds.neighbours nearest Gaussians (itself excluded), row by row; empty: no vote.
// Steps:
//  1. dynamic if displacement > tau_delta or scale change > tau_s;
//  2. back to static if its E_L1 > tau_E (a fitting artefact rather than motion);
//  3. each Gaussian takes the class of the majority of itself and its K neighbours
//     (computed from the step-2 classes, so the vote does not depend on the order).
std::vector<uint8_t> ClassifyDynamic(const LookaheadMeasures& measures,
                                     const DecouplingThresholds& thresholds,
                                     const std::vector<uint32_t>& neighbours);

}  // namespace m4d

#endif  // M4D_ENCODER_DECOUPLING_MOTION_CLASSIFICATION_H_
