#include "encoder/src/pipeline/motion_decision.h"

namespace m4d {

Status DecideMotion(const GaussianSet& still, const GaussianSet& moved, double min_gain,
                    TrainingPsnrMeter* meter, MotionDecision* decision) {
  double with = 0, without = 0;
  M4D_RETURN_IF_ERROR(meter->Measure(moved, &with));
  M4D_RETURN_IF_ERROR(meter->Measure(still, &without));
  decision->gain = with - without;
  decision->skip = !(decision->gain > min_gain);
  return Status::Ok();
}

}  // namespace m4d
