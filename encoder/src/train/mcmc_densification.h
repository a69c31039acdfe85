// McmcDensification: 3D Gaussian Splatting as Markov Chain Monte Carlo (Kheradmand et al.,
// NeurIPS 2024) as a DensificationStrategy. The Gaussians are samples, and training moves
// them rather than creating and deleting them:
// - every refine_interval iterations in [refine_from, refine_until): Gaussians whose opacity
//   is at or below min_opacity are relocated onto opaque ones (sampled in proportion to
//   opacity), then growth adds Gaussians the same way, up to max_gaussians exactly;
// - a source copied into N Gaussians (itself included) keeps its rendered footprint: each
//   gets opacity 1 - (1 - o)^(1/N) and its scales times o / sum_{i=1..N} sum_{k=0..i-1}
//   C(i-1, k) (-1)^k o'^(k+1) / sqrt(k+1), the paper's moment matching (RelocatedOpacityScale);
//   the rows it touches start with zero Adam moments;
// - after every Adam step each position moves by Sigma n sigmoid(100 (1 - o - 0.995))
//   noise_learning_rate lr (n standard normal, Sigma the Gaussian's covariance, lr the position
//   learning rate): transparent Gaussians explore, opaque ones stay;
// - the loss gains opacity_regularization times the mean opacity and scale_regularization
//   times the mean scale (L1), so that unneeded Gaussians fade and are relocated.
// No Gaussian is ever removed, so no event can lose part of the model, and the count is the
// budget a rate point asks for.
#ifndef M4D_ENCODER_TRAIN_MCMC_DENSIFICATION_H_
#define M4D_ENCODER_TRAIN_MCMC_DENSIFICATION_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "encoder/src/train/densification_strategy.h"

namespace m4d {

struct McmcSettings {
  size_t max_gaussians = 1000000;  // growth stops here
  float growth = 0.05f;            // of the count, per refinement
  float min_opacity = 0.005f;      // relocated at or below
  float noise_learning_rate = 5e5f;
  float opacity_regularization = 0.01f;
  float scale_regularization = 0.01f;
  int refine_from = 500;
  int refine_until = 25000;
  int refine_interval = 100;
  size_t frozen = 0;  // the first this many Gaussians are never moved nor sampled
};

// The paper's limit on the copies of one source in one refinement.
constexpr int kMaxRelocationCopies = 51;

// Opacity and scale factor of each of `copies` Gaussians (1..kMaxRelocationCopies) that
// together replace one of `opacity` (in (0, 1)).
void RelocatedOpacityScale(float opacity, int copies, float* new_opacity, float* scale_factor);

class McmcDensification : public DensificationStrategy {
 public:
  explicit McmcDensification(const McmcSettings& settings) : settings_(settings) {}

  std::unique_ptr<DensificationStrategy> Clone() const override {
    return std::make_unique<McmcDensification>(*this);
  }
  DensificationStrategyKind kind() const override { return DensificationStrategyKind::kMcmc; }
  void Reset(size_t) override { counts_ = StrategyCounts(); }
  Status AfterBackward(const StrategyStep& step, const StrategyState& state,
                       StrategyOutcome* outcome) override;
  void Regularize(const GaussianModel& model, GaussianModel* gradients) const override;
  void AfterStep(const StrategyStep& step, const StrategyState& state) override;
  const StrategyCounts& counts() const override { return counts_; }

 private:
  // Relocates the transparent Gaussians; returns how many.
  size_t Relocate(const StrategyState& state);
  // Grows toward the budget; returns how many were added.
  size_t Grow(const StrategyState& state);

  McmcSettings settings_;
  StrategyCounts counts_;
};

// Moves rows `sources` (with repeats) to their share of each source: every distinct source's
// opacity and scales follow RelocatedOpacityScale for its count plus one, and its moments
// are zeroed. The copies themselves are the caller's.
void ShareSources(const std::vector<uint32_t>& sources, GaussianModel* model,
                  AdamOptimizer* optimizer);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_MCMC_DENSIFICATION_H_
