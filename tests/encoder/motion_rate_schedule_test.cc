#include "encoder/src/pipeline/motion_rate_schedule.h"

#include <gtest/gtest.h>

namespace m4d {
namespace {

TEST(MotionRateScheduleTest, FallsAlongTheGopToItsFloor) {
  const double lambda = 1.2e-4;
  // The first inter frame keeps lambda_2; each later one loses `decay` of it.
  EXPECT_DOUBLE_EQ(MotionRateWeight(lambda, 1, 0.06), lambda);
  EXPECT_DOUBLE_EQ(MotionRateWeight(lambda, 2, 0.06), 0.94 * lambda);
  EXPECT_DOUBLE_EQ(MotionRateWeight(lambda, 9, 0.06), (1.0 - 8 * 0.06) * lambda);
  // From the 13th inter frame on, 1 - 0.06 * 12 is below the floor.
  EXPECT_DOUBLE_EQ(MotionRateWeight(lambda, 13, 0.06), kMinMotionRateShare * lambda);
  EXPECT_DOUBLE_EQ(MotionRateWeight(lambda, 300, 0.06), kMinMotionRateShare * lambda);
  for (int frame = 2; frame < 20; ++frame) {
    EXPECT_LE(MotionRateWeight(lambda, frame, 0.06), MotionRateWeight(lambda, frame - 1, 0.06));
  }
}

TEST(MotionRateScheduleTest, NoDecayIsThePapersConstantWeight) {
  for (int frame : {0, 1, 2, 50}) EXPECT_DOUBLE_EQ(MotionRateWeight(5e-4, frame, 0.0), 5e-4);
  EXPECT_DOUBLE_EQ(MotionRateWeight(5e-4, 3, 1.0), kMinMotionRateShare * 5e-4);
  EXPECT_DOUBLE_EQ(MotionRateWeight(0.0, 5, 0.06), 0.0);
}

}  // namespace
}  // namespace m4d
