// The random start's schedule (random_start_schedule.h): taken after points drawn at random with
// adaptive density control, and only then.
#include <gtest/gtest.h>

#include <vector>

#include "encoder/src/train/random_start_schedule.h"

namespace m4d {
namespace {

const std::vector<KeyframeStart> kSwept = {{"photo-consistent points, 3 views", 5000, true}};
const std::vector<KeyframeStart> kFellThrough = {
    {"photo-consistent points, 3 views", 10, false},
    {"random in the cameras' box, with the points found", 3000, true, true},
    {"background shell", 500, true}};

TEST(RandomStartScheduleTest, TakenAfterARandomStartWithAdaptiveDensityControl) {
  KeyframeTrainingOptions adc = KeyframeTrainingOptions::Short(2000);
  adc.strategy = DensificationStrategyKind::kAdaptiveDensityControl;
  KeyframeTrainingOptions mcmc = adc;
  mcmc.strategy = DensificationStrategyKind::kMcmc;
  EXPECT_TRUE(TakesRandomStartSchedule(adc, kFellThrough));
  EXPECT_FALSE(TakesRandomStartSchedule(adc, kSwept));
  EXPECT_FALSE(TakesRandomStartSchedule(mcmc, kFellThrough));
  EXPECT_FALSE(TakesRandomStartSchedule(adc, {}));
}

TEST(RandomStartScheduleTest, ScalesTheRatesAndDropsTheReset) {
  const KeyframeTrainingOptions given = KeyframeTrainingOptions::Short(2000);
  ASSERT_GT(given.opacity_reset_interval, 0);
  RandomStartSchedule schedule;
  schedule.position_rate = 3.0f;
  schedule.scaling_rate = 2.0f;
  const KeyframeTrainingOptions o = OptionsForStart(given, kFellThrough, schedule);
  EXPECT_FLOAT_EQ(o.learning_rates.position.initial, 3.0f * given.learning_rates.position.initial);
  EXPECT_FLOAT_EQ(o.learning_rates.position.final, 3.0f * given.learning_rates.position.final);
  EXPECT_EQ(o.learning_rates.position.max_steps, given.learning_rates.position.max_steps);
  EXPECT_FLOAT_EQ(o.learning_rates.scaling, 2.0f * given.learning_rates.scaling);
  EXPECT_FLOAT_EQ(o.learning_rates.opacity, given.learning_rates.opacity);
  EXPECT_FLOAT_EQ(o.densification.gradient_threshold, given.densification.gradient_threshold);
  EXPECT_EQ(o.opacity_reset_interval, 0);
  EXPECT_EQ(o.iterations, given.iterations);

  schedule.opacity_reset = true;
  EXPECT_EQ(OptionsForStart(given, kFellThrough, schedule).opacity_reset_interval,
            given.opacity_reset_interval);
  // A swept start trains as given.
  const KeyframeTrainingOptions same = OptionsForStart(given, kSwept, schedule);
  EXPECT_FLOAT_EQ(same.learning_rates.position.initial, given.learning_rates.position.initial);
  EXPECT_EQ(same.opacity_reset_interval, given.opacity_reset_interval);
}

}  // namespace
}  // namespace m4d
