// Appearance estimation of one inter frame (bitstream 0.3's APPEARANCE packet; not in the paper): a
// change of each dynamic Gaussian's SH DC colour, in quantization steps, trained with the frame's
// motion from the same renders. The paper keeps colours fixed within a GOP; on the default scene
// the held-out view then drifts over a GOP, only on moving content, because shading changes as
// parts turn, and refitting each Gaussian's DC per frame removes about half of that drift
// (docs/results/2026-11-30-readme-notebook.md, "Moving parts change colour within a GOP").
//
// Like the grid, the values train under simulated quantization (uniform noise of one step)
// and a rate term: their bits under a learned factorized entropy model, one density per
// colour channel.
#ifndef M4D_ENCODER_MOTION_APPEARANCE_ESTIMATION_H_
#define M4D_ENCODER_MOTION_APPEARANCE_ESTIMATION_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/src/motion/logistic_entropy_model.h"
#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/training_random.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// The training views that train no colour change when every k-th one is held out for the
// appearance decision: k-1, 2k-1, ... of `view_count` (none for k <= 0).
std::vector<int> AppearanceCheckViews(int view_count, int every);
bool AnyAppearanceCheckView(const std::vector<int>& views, int every);

class AppearanceEstimation {
 public:
  // For a dynamic set of `gaussians`; values start at zero.
  AppearanceEstimation(size_t gaussians, float step, float learning_rate,
                       float entropy_learning_rate);

  // The SH of `set` with each DC coefficient changed by (value + noise) * step, noise uniform
  // in [-1/2, 1/2) when simulate_quantization; valid until the next call.
  const float* NoisySh(const GaussianSet& set, bool simulate_quantization, TrainingRandom* rng);

  // One step: d_dc holds dL/d(DC) of the rendered set, 3 per Gaussian; the rate term adds
  // rate_weight * bits of the noisy values. lr_scale multiplies the learning rate.
  void Step(const float* d_dc, double rate_weight, float lr_scale);

  // The values rounded to integers within the writer's +-2047.
  std::vector<int32_t> Rounded() const;
  // Bits of integer values under the entropy model.
  double Bits(const std::vector<int32_t>& values) const;

  float step() const { return step_; }

 private:
  size_t n_;
  float step_;
  std::vector<float> values_;  // in steps, r, g, b per Gaussian
  std::vector<float> noisy_;
  std::vector<float> sh_;
  std::vector<float> grad_;
  AdamOptimizer adam_;
  int parameter_ = 0;
  float learning_rate_;
  LogisticEntropyModel entropy_;
  AdamOptimizer entropy_adam_;
  int entropy_parameter_ = 0;
  std::vector<float> entropy_grad_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_APPEARANCE_ESTIMATION_H_
