#include "encoder/src/pipeline/appearance_decision.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "sdk/src/decode/appearance_application.h"

namespace m4d {

double RequiredAppearanceGain(double min_gain, double gain_per_doubling, size_t frame_bytes,
                              size_t appearance_bytes) {
  if (min_gain < 0 || frame_bytes == 0) return min_gain;
  const double doublings = std::log2(static_cast<double>(frame_bytes + appearance_bytes) /
                                     static_cast<double>(frame_bytes));
  return std::max(min_gain, gain_per_doubling * doublings);
}

Status DecideAppearance(const AppearanceUpdate& appearance, double min_gain,
                        const std::vector<int>& check_views, TrainingPsnrMeter* meter,
                        GaussianSet* moved, AppearanceDecision* decision) {
  GaussianSet changed = *moved;
  ApplyAppearanceUpdate(appearance, &changed);
  double with = 0, without = 0;
  if (check_views.empty()) {
    M4D_RETURN_IF_ERROR(meter->Measure(changed, &with));
    M4D_RETURN_IF_ERROR(meter->Measure(*moved, &without));
  } else {
    M4D_RETURN_IF_ERROR(meter->MeasureViews(changed, check_views, &with));
    M4D_RETURN_IF_ERROR(meter->MeasureViews(*moved, check_views, &without));
  }
  decision->gain = with - without;
  decision->skipped = !(decision->gain > min_gain);
  if (!decision->skipped) *moved = std::move(changed);
  return Status::Ok();
}

}  // namespace m4d
