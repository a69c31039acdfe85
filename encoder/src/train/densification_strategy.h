// DensificationStrategy: how keyframe training grows, prunes and moves its set of Gaussians,
// behind one interface (as gsplat's Strategy), so that the trainer runs either:
// - AdaptiveDensityControl (adaptive_density_control.h): the reference 3DGS's clone, split,
//   prune and opacity reset, driven by view-space gradients;
// - McmcDensification (mcmc_densification.h): 3DGS as Markov Chain Monte Carlo (Kheradmand
//   et al. 2024), which relocates transparent Gaussians onto opaque ones, grows to an exact
//   budget and never removes any.
//
// Within an iteration the trainer calls AfterBackward once the gradients are known (the
// strategy gathers statistics and edits the model when its schedule says so), then, unless
// the rows changed, adds Regularize's gradients and steps Adam, then calls AfterStep.
#ifndef M4D_ENCODER_TRAIN_DENSIFICATION_STRATEGY_H_
#define M4D_ENCODER_TRAIN_DENSIFICATION_STRATEGY_H_

#include <cstddef>
#include <memory>
#include <string>
#include <utility>

#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/training_random.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

enum class DensificationStrategyKind { kAdaptiveDensityControl, kMcmc };

// What a strategy sees of one iteration.
struct StrategyStep {
  int iteration = 0;                        // 1-based
  float position_learning_rate = 0;         // this iteration's, in world units
  const ProjectedSplats* splats = nullptr;  // the rendered view's projection
  const float* mean2d = nullptr;            // its view-space position gradients, 2 per Gaussian
  int width = 0, height = 0;                // of the rendered view
};

// What a strategy edits: rows of the model and the optimizer stay aligned.
struct StrategyState {
  GaussianModel* model = nullptr;
  AdamOptimizer* optimizer = nullptr;
  TrainingRandom* rng = nullptr;
};

// What AfterBackward did.
struct StrategyOutcome {
  bool rows_changed = false;  // the trainer skips this iteration's Adam step
  GaussianParameter skip_step = kGaussianParameterCount;  // or skips this parameter's step
  size_t removed = 0;                                     // Gaussians removed by this event
  size_t before = 0;  // the model's size it removed from (ADC: after its clones and splits)
};

// Totals over a run.
struct StrategyCounts {
  size_t cloned = 0;
  size_t split = 0;      // parents replaced by two children each
  size_t pruned = 0;     // removed besides the split parents
  size_t relocated = 0;  // transparent Gaussians moved onto opaque ones
  size_t added = 0;      // grown by sampling (MCMC)
};

class DensificationStrategy {
 public:
  virtual ~DensificationStrategy() = default;
  // A copy in the same state (a trainer's copy continues as a branch).
  virtual std::unique_ptr<DensificationStrategy> Clone() const = 0;
  virtual DensificationStrategyKind kind() const = 0;
  // Starts for a model of `count` Gaussians.
  virtual void Reset(size_t count) = 0;
  virtual Status AfterBackward(const StrategyStep& step, const StrategyState& state,
                               StrategyOutcome* outcome) = 0;
  // Adds the gradients of the strategy's own loss terms to `gradients` (same rows as `model`).
  virtual void Regularize(const GaussianModel& model, GaussianModel* gradients) const = 0;
  virtual void AfterStep(const StrategyStep& step, const StrategyState& state) = 0;
  virtual const StrategyCounts& counts() const = 0;
};

// Owns a strategy and copies it with Clone(), so that a trainer stays copyable.
class StrategyHolder {
 public:
  StrategyHolder() = default;
  explicit StrategyHolder(std::unique_ptr<DensificationStrategy> s) : strategy_(std::move(s)) {}
  StrategyHolder(const StrategyHolder& o)
      : strategy_(o.strategy_ ? o.strategy_->Clone() : nullptr) {}
  StrategyHolder& operator=(const StrategyHolder& o) {
    strategy_ = o.strategy_ ? o.strategy_->Clone() : nullptr;
    return *this;
  }
  StrategyHolder(StrategyHolder&&) = default;
  StrategyHolder& operator=(StrategyHolder&&) = default;
  DensificationStrategy* operator->() const { return strategy_.get(); }
  explicit operator bool() const { return strategy_ != nullptr; }

 private:
  std::unique_ptr<DensificationStrategy> strategy_;
};

const char* StrategyName(DensificationStrategyKind kind);
// "adc" or "mcmc"; false for another name.
bool ParseStrategyName(const std::string& name, DensificationStrategyKind* kind);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_DENSIFICATION_STRATEGY_H_
