#include "encoder/src/pipeline/motion_rate_schedule.h"

#include <algorithm>

namespace m4d {

double MotionRateWeight(double lambda, int frame_in_gop, double decay) {
  const double share = 1.0 - decay * static_cast<double>(std::max(0, frame_in_gop - 1));
  return lambda * std::max(kMinMotionRateShare, std::min(1.0, share));
}

}  // namespace m4d
