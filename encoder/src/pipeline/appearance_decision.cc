#include "encoder/src/pipeline/appearance_decision.h"

#include <utility>

#include "sdk/src/decode/appearance_application.h"

namespace m4d {

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
