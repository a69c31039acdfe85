#include "encoder/src/train/learning_rate_schedule.h"

#include <algorithm>
#include <cmath>

namespace m4d {

float ExponentialDecay::At(int step) const {
  if (step < 0 || (initial == 0 && final == 0)) return 0.0f;
  double delay = 1.0;
  if (delay_steps > 0) {
    const double s = std::clamp(static_cast<double>(step) / delay_steps, 0.0, 1.0);
    delay = delay_multiplier + (1.0 - delay_multiplier) * std::sin(0.5 * 3.141592653589793 * s);
  }
  const double t = std::clamp(static_cast<double>(step) / std::max(max_steps, 1), 0.0, 1.0);
  const double log_lerp =
      std::exp(std::log(double{initial}) * (1.0 - t) + std::log(double{final}) * t);
  return static_cast<float>(delay * log_lerp);
}

}  // namespace m4d
