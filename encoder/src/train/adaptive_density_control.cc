#include "encoder/src/train/adaptive_density_control.h"

namespace m4d {

void AdaptiveDensityControl::Reset(size_t count) {
  stats_.Reset(count);
  last_reset_ = 0;
  counts_ = StrategyCounts();
}

Status AdaptiveDensityControl::AfterBackward(const StrategyStep& step, const StrategyState& state,
                                             StrategyOutcome* outcome) {
  *outcome = StrategyOutcome();
  outcome->before = state.model->size();
  const int it = step.iteration;
  const AdaptiveDensitySchedule& s = schedule_;
  if (it >= s.densify_until) return Status::Ok();
  stats_.Accumulate(*step.splats, step.mean2d, step.width, step.height);
  const bool recovering = last_reset_ > 0 && it - last_reset_ < s.reset_recovery;
  if (it > s.densify_from && s.densify_interval > 0 && it % s.densify_interval == 0 &&
      !recovering) {
    const bool prune_by_size = s.opacity_reset_interval > 0 && it > s.opacity_reset_interval;
    DensifyCounts c;
    M4D_RETURN_IF_ERROR(DensifyAndPrune(s.settings, scene_extent_, prune_by_size, state.rng,
                                        state.model, state.optimizer, &stats_, &c));
    counts_.cloned += c.cloned;
    counts_.split += c.split;
    counts_.pruned += c.pruned;
    outcome->rows_changed = true;
    // The prune bound holds for the model grown by this step's clones and splits.
    outcome->before = state.model->size() + c.split + c.pruned;
    outcome->removed = c.pruned;
  }
  if (s.opacity_reset_interval > 0 && it % s.opacity_reset_interval == 0) {
    ResetOpacity(s.opacity_reset_value, state.model, state.optimizer);
    outcome->skip_step = kParamOpacityLogits;
    last_reset_ = it;
  }
  return Status::Ok();
}

}  // namespace m4d
