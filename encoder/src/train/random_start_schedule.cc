#include "encoder/src/train/random_start_schedule.h"

namespace m4d {

bool TakesRandomStartSchedule(const KeyframeTrainingOptions& options,
                              const std::vector<KeyframeStart>& starts) {
  if (options.strategy != DensificationStrategyKind::kAdaptiveDensityControl) return false;
  for (const KeyframeStart& start : starts) {
    if (start.taken && start.random) return true;
  }
  return false;
}

KeyframeTrainingOptions OptionsForStart(const KeyframeTrainingOptions& options,
                                        const std::vector<KeyframeStart>& starts,
                                        const RandomStartSchedule& schedule) {
  if (!TakesRandomStartSchedule(options, starts)) return options;
  KeyframeTrainingOptions o = options;
  o.learning_rates.position.initial *= schedule.position_rate;
  o.learning_rates.position.final *= schedule.position_rate;
  o.learning_rates.scaling *= schedule.scaling_rate;
  if (!schedule.opacity_reset) o.opacity_reset_interval = 0;
  return o;
}

}  // namespace m4d
