// AdaptiveDensityControl: the reference 3DGS's densification as a DensificationStrategy.
// While the iteration is below densify_until it gathers view-space gradient statistics,
// densifies and prunes (densification.h) every densify_interval iterations after
// densify_from, and resets opacities every opacity_reset_interval iterations; after a reset
// nothing is densified or pruned for reset_recovery iterations. Size pruning starts after the
// first reset, as in the reference.
#ifndef M4D_ENCODER_TRAIN_ADAPTIVE_DENSITY_CONTROL_H_
#define M4D_ENCODER_TRAIN_ADAPTIVE_DENSITY_CONTROL_H_

#include <memory>

#include "encoder/src/train/densification.h"
#include "encoder/src/train/densification_strategy.h"

namespace m4d {

struct AdaptiveDensitySchedule {
  DensificationSettings settings;
  int densify_from = 500;
  int densify_until = 15000;
  int densify_interval = 100;
  int opacity_reset_interval = 3000;  // 0: never
  float opacity_reset_value = 0.01f;
  int reset_recovery = 100;
};

class AdaptiveDensityControl : public DensificationStrategy {
 public:
  AdaptiveDensityControl(const AdaptiveDensitySchedule& schedule, float scene_extent)
      : schedule_(schedule), scene_extent_(scene_extent) {}

  std::unique_ptr<DensificationStrategy> Clone() const override {
    return std::make_unique<AdaptiveDensityControl>(*this);
  }
  DensificationStrategyKind kind() const override {
    return DensificationStrategyKind::kAdaptiveDensityControl;
  }
  void Reset(size_t count) override;
  Status AfterBackward(const StrategyStep& step, const StrategyState& state,
                       StrategyOutcome* outcome) override;
  void Regularize(const GaussianModel&, GaussianModel*) const override {}
  void AfterStep(const StrategyStep&, const StrategyState&) override {}
  const StrategyCounts& counts() const override { return counts_; }

 private:
  AdaptiveDensitySchedule schedule_;
  float scene_extent_;
  DensificationStats stats_;
  int last_reset_ = 0;  // iteration of the last opacity reset (0: none yet)
  StrategyCounts counts_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_ADAPTIVE_DENSITY_CONTROL_H_
