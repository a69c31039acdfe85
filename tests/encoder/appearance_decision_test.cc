// The bar a colour change must clear (pipeline/appearance_decision.h): the minimum gain, raised
// by its bytes against the frame's.
#include "encoder/src/pipeline/appearance_decision.h"

#include <gtest/gtest.h>

namespace m4d {
namespace {

TEST(RequiredAppearanceGainTest, DoublingTheFrameCostsTheBoundOnce) {
  EXPECT_DOUBLE_EQ(RequiredAppearanceGain(0.0, 0.5, 1000, 1000), 0.5);
  EXPECT_DOUBLE_EQ(RequiredAppearanceGain(0.0, 0.5, 1000, 3000), 1.0);
  EXPECT_NEAR(RequiredAppearanceGain(0.0, 0.5, 12000, 5000), 0.5 * 0.50250, 1e-4);
}

TEST(RequiredAppearanceGainTest, TheMinimumGainStaysTheFloor) {
  EXPECT_DOUBLE_EQ(RequiredAppearanceGain(0.3, 0.5, 1000, 10), 0.3);
  EXPECT_DOUBLE_EQ(RequiredAppearanceGain(0.0, 0.0, 1000, 5000), 0.0);
}

TEST(RequiredAppearanceGainTest, ANegativeMinimumCodesItAlways) {
  EXPECT_DOUBLE_EQ(RequiredAppearanceGain(-1.0, 0.5, 1000, 5000), -1.0);
}

}  // namespace
}  // namespace m4d
