#include "encoder/src/decoupling/temporal_change.h"

#include <gtest/gtest.h>

#include <random>

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48;

// A smooth gradient with a bright 10x10 square at (x, y), plus noise of `sigma`.
Image Frame(int x, int y, float sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  Image image(kWidth, kHeight, 3);
  for (int j = 0; j < kHeight; ++j) {
    for (int i = 0; i < kWidth; ++i) {
      const bool square = i >= x && i < x + 10 && j >= y && j < y + 10;
      for (int c = 0; c < 3; ++c) {
        const float base = square ? 0.9f : 0.2f + 0.3f * i / kWidth;
        image.row(j)[3 * i + c] = base + (sigma > 0 ? noise(rng) : 0.0f);
      }
    }
  }
  return image;
}

TEST(TemporalChangeTest, NoiseAloneChangesNothing) {
  TemporalChange change;
  ASSERT_TRUE(
      MeasureTemporalChange(Frame(5, 5, 0.02f, 1), Frame(5, 5, 0.02f, 2), {}, &change).ok());
  EXPECT_GT(change.noise_level, 0.005f);
  EXPECT_LT(change.changed_share, 0.01f);
}

TEST(TemporalChangeTest, MarksWhatMovedAndItsEdges) {
  TemporalChange change;
  ASSERT_TRUE(
      MeasureTemporalChange(Frame(5, 5, 0.02f, 1), Frame(30, 20, 0.02f, 2), {}, &change).ok());
  auto at = [&](int x, int y) { return change.mask[static_cast<size_t>(y) * kWidth + x]; };
  EXPECT_EQ(at(9, 9), 1.0f);    // where the square was
  EXPECT_EQ(at(34, 24), 1.0f);  // where it is
  EXPECT_EQ(at(3, 3), 1.0f);    // dilated past its edge
  EXPECT_EQ(at(55, 40), 0.0f);  // far from both
  EXPECT_GT(change.changed_share, 2 * 100.0f / (kWidth * kHeight));
  EXPECT_LT(change.changed_share, 0.25f);
}

TEST(TemporalChangeTest, RejectsMismatchedImages) {
  TemporalChange change;
  EXPECT_EQ(
      MeasureTemporalChange(Frame(5, 5, 0, 1), Image(kWidth, kHeight + 1, 3), {}, &change).code(),
      M4D_ERR_INVALID_ARG);
  TemporalChangeOptions bad;
  bad.radius = -1;
  EXPECT_EQ(MeasureTemporalChange(Frame(5, 5, 0, 1), Frame(5, 5, 0, 1), bad, &change).code(),
            M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
