// The training views that judge the colour change instead of training it
// (appearance_estimation.h, appearance_decision.h).
#include <gtest/gtest.h>

#include <vector>

#include "encoder/src/motion/appearance_estimation.h"

namespace m4d {
namespace {

TEST(AppearanceCheckViewsTest, EveryKthViewFromTheKth) {
  EXPECT_EQ(AppearanceCheckViews(10, 4), (std::vector<int>{3, 7}));
  EXPECT_EQ(AppearanceCheckViews(27, 4), (std::vector<int>{3, 7, 11, 15, 19, 23}));
  EXPECT_TRUE(AppearanceCheckViews(3, 4).empty());
  EXPECT_TRUE(AppearanceCheckViews(10, 0).empty());
}

TEST(AppearanceCheckViewsTest, ABatchWithACheckViewTrainsNoColourChange) {
  EXPECT_FALSE(AnyAppearanceCheckView({0, 1, 2}, 4));
  EXPECT_TRUE(AnyAppearanceCheckView({2, 3}, 4));
  EXPECT_TRUE(AnyAppearanceCheckView({11}, 4));
  EXPECT_FALSE(AnyAppearanceCheckView({3, 7}, 0));
}

}  // namespace
}  // namespace m4d
