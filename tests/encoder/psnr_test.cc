// PSNR and MSE (metrics/psnr.h).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "encoder/src/metrics/psnr.h"

namespace m4d {
namespace {

TEST(PsnrTest, ConstantOffsetOfTenthIsTwentyDecibels) {
  Image a(7, 5, 3), b(7, 5, 3);
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    a.pixels[i] = 0.05f * static_cast<float>(i % 13);
    b.pixels[i] = a.pixels[i] + (i % 2 ? 0.1f : -0.1f);
  }
  double mse = 0, psnr = 0;
  ASSERT_TRUE(MeanSquaredError(a, b, &mse).ok());
  ASSERT_TRUE(Psnr(a, b, &psnr).ok());
  // 0.1f is not exactly 0.1: the float sums differ from 0.1 by a few 1e-8.
  EXPECT_NEAR(mse, 0.01, 1e-8);
  EXPECT_NEAR(psnr, 20.0, 1e-5);
}

TEST(PsnrTest, KnownMseValues) {
  Image a(4, 4, 1, 0.5f), b(4, 4, 1, 0.5f);
  b.pixels[0] = 0.75f;  // one sample off by 1/4: MSE = (1/16) / 16 = 2^-8
  double mse = 0, psnr = 0;
  ASSERT_TRUE(MeanSquaredError(a, b, &mse).ok());
  ASSERT_TRUE(Psnr(a, b, &psnr).ok());
  EXPECT_EQ(mse, 1.0 / 256);
  EXPECT_NEAR(psnr, 80 * std::log10(2.0), 1e-12);
}

TEST(PsnrTest, EqualImagesGiveInfinity) {
  const Image a(6, 4, 3, 0.3f);
  double psnr = 0;
  ASSERT_TRUE(Psnr(a, a, &psnr).ok());
  EXPECT_EQ(psnr, std::numeric_limits<double>::infinity());
}

TEST(PsnrTest, MaskSelectsAndWeightsPixels) {
  Image a(4, 2, 3, 0.5f), b(4, 2, 3, 0.5f), mask(4, 2, 1, 0.0f);
  // Left half: off by 0.1 and selected; right half: off by 0.4 and masked out.
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) {
      for (int c = 0; c < 3; ++c) b.at(x, y, c) = x < 2 ? 0.625f : 0.1f;
      mask.at(x, y, 0) = x < 2 ? 1.0f : 0.0f;
    }
  }
  double psnr = 0, unmasked = 0;
  ASSERT_TRUE(PsnrMasked(a, b, mask, &psnr).ok());
  ASSERT_TRUE(Psnr(a, b, &unmasked).ok());
  EXPECT_NEAR(psnr, -10 * std::log10(0.125 * 0.125), 1e-12);
  EXPECT_LT(unmasked, psnr - 5);

  // Fractional weights: a weighted mean of the squared errors.
  mask.at(2, 0, 0) = 0.5f;
  ASSERT_TRUE(PsnrMasked(a, b, mask, &psnr).ok());
  const double mse = (4 * 0.125 * 0.125 + 0.5 * 0.4 * 0.4) / 4.5;
  EXPECT_NEAR(psnr, -10 * std::log10(mse), 1e-6);
}

TEST(PsnrTest, RejectsBadInput) {
  double v = 0;
  const Image a(4, 4, 3), b(4, 4, 3);
  EXPECT_EQ(Psnr(a, Image(4, 4, 1), &v).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(MeanSquaredError(a, Image(5, 4, 3), &v).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(PsnrMasked(a, b, Image(4, 4, 1, 0.0f), &v).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(PsnrMasked(a, b, Image(4, 4, 3, 1.0f), &v).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(PsnrMasked(a, b, Image(4, 3, 1, 1.0f), &v).code(), M4D_ERR_INVALID_ARG);
  Image negative(4, 4, 1, 1.0f);
  negative.pixels[3] = -1.0f;
  EXPECT_EQ(PsnrMasked(a, b, negative, &v).code(), M4D_ERR_INVALID_ARG);
  Image nan_mask(4, 4, 1, 1.0f);
  nan_mask.pixels[5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(PsnrMasked(a, b, nan_mask, &v).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
