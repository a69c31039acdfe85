// SSIM (metrics/ssim.h) against the direct double-precision definition
// (tests/encoder/ssim_reference.h).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "encoder/src/metrics/ssim.h"
#include "tests/encoder/ssim_reference.h"

namespace m4d {
namespace {

using testing::CorrelatedImage;
using testing::DoubleImage;
using testing::RandomImage;
using testing::ReferenceSsim;
using testing::SsimDerivative;

struct Shape {
  int width, height, channels;
};

// Float filtering against double: the mean SSIM agrees to this absolute error.
constexpr double kValueTolerance = 1e-6;

TEST(SsimTest, MatchesDirectDefinitionBothConventions) {
  std::mt19937 rng(7);
  const Shape shapes[] = {{17, 13, 1}, {17, 13, 3}, {32, 24, 1}, {32, 24, 3}, {11, 11, 3}};
  for (const Shape& s : shapes) {
    const Image x = RandomImage(s.width, s.height, s.channels, &rng);
    const Image y = CorrelatedImage(x, &rng);
    double padded = 0, valid = 0;
    ASSERT_TRUE(SsimZeroPadded(x, y, &padded).ok());
    ASSERT_TRUE(SsimValid(x, y, &valid).ok());
    const double ref_padded = ReferenceSsim(DoubleImage(x), DoubleImage(y), false);
    const double ref_valid = ReferenceSsim(DoubleImage(x), DoubleImage(y), true);
    EXPECT_NEAR(padded, ref_padded, kValueTolerance) << s.width << "x" << s.height;
    EXPECT_NEAR(valid, ref_valid, kValueTolerance) << s.width << "x" << s.height;
    // The conventions differ: zero padding darkens the border statistics.
    EXPECT_GT(std::fabs(padded - valid), 1e-3);
  }
}

// 160 x 120 x 3 is large enough to be split across threads where there are several.
TEST(SsimTest, LargeImageMatchesDirectDefinition) {
  std::mt19937 rng(8);
  const Image x = RandomImage(160, 120, 3, &rng);
  const Image y = CorrelatedImage(x, &rng);
  double padded = 0, valid = 0;
  ASSERT_TRUE(SsimZeroPadded(x, y, &padded).ok());
  ASSERT_TRUE(SsimValid(x, y, &valid).ok());
  EXPECT_NEAR(padded, ReferenceSsim(DoubleImage(x), DoubleImage(y), false), kValueTolerance);
  EXPECT_NEAR(valid, ReferenceSsim(DoubleImage(x), DoubleImage(y), true), kValueTolerance);
}

TEST(SsimTest, IdenticalImagesGiveOneAndZeroGradient) {
  std::mt19937 rng(9);
  const Image x = RandomImage(32, 24, 3, &rng);
  double padded = 0, valid = 0;
  Image grad;
  ASSERT_TRUE(SsimZeroPadded(x, x, &padded, &grad).ok());
  ASSERT_TRUE(SsimValid(x, x, &valid).ok());
  EXPECT_NEAR(padded, 1.0, 1e-6);
  EXPECT_NEAR(valid, 1.0, 1e-6);
  // SSIM is at its maximum: the gradient (entries of order 1 / N = 4e-4 elsewhere) vanishes.
  for (float g : grad.pixels) ASSERT_NEAR(g, 0.0f, 1e-8f);
}

TEST(SsimTest, DissimilarImagesScoreLow) {
  std::mt19937 rng(10);
  const Image x = RandomImage(32, 24, 1, &rng);
  const Image y = RandomImage(32, 24, 1, &rng);
  double ssim = 1;
  ASSERT_TRUE(SsimValid(x, y, &ssim).ok());
  EXPECT_LT(std::fabs(ssim), 0.1);
}

// The analytic gradient against central differences of the double-precision definition:
// max |analytic - numeric| <= kGradientTolerance * max |numeric|, over every sample.
constexpr double kGradientTolerance = 1e-4;

double MaxGradientError(const Image& x, const Image& y, const Image& grad, double* max_ref) {
  const DoubleImage dx(x), dy(y);
  double max_error = 0;
  *max_ref = 0;
  for (int py = 0; py < x.height; ++py) {
    for (int px = 0; px < x.width; ++px) {
      for (int c = 0; c < x.channels; ++c) {
        const double numeric = SsimDerivative(dx, dy, px, py, c, 1e-5);
        max_error = std::max(max_error, std::fabs(grad.at(px, py, c) - numeric));
        *max_ref = std::max(*max_ref, std::fabs(numeric));
      }
    }
  }
  return max_error;
}

TEST(SsimTest, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(11);
  const Shape shapes[] = {{17, 13, 1}, {17, 13, 3}, {32, 24, 3}};
  for (const Shape& s : shapes) {
    const Image x = RandomImage(s.width, s.height, s.channels, &rng);
    const Image y = CorrelatedImage(x, &rng);
    double ssim = 0, ssim_no_grad = 0;
    Image grad;
    ASSERT_TRUE(SsimZeroPadded(x, y, &ssim, &grad).ok());
    ASSERT_TRUE(SsimZeroPadded(x, y, &ssim_no_grad).ok());
    EXPECT_EQ(ssim, ssim_no_grad);
    ASSERT_EQ(grad.width, x.width);
    ASSERT_EQ(grad.height, x.height);
    ASSERT_EQ(grad.channels, x.channels);
    double max_ref = 0;
    const double error = MaxGradientError(x, y, grad, &max_ref);
    EXPECT_LE(error, kGradientTolerance * max_ref)
        << s.width << "x" << s.height << "x" << s.channels;
  }
}

// Smooth content has small local variances, where C2 dominates the denominators.
TEST(SsimTest, GradientMatchesFiniteDifferencesOnSmoothContent) {
  Image x(19, 15, 3), y(19, 15, 3);
  for (int py = 0; py < x.height; ++py) {
    for (int px = 0; px < x.width; ++px) {
      for (int c = 0; c < 3; ++c) {
        x.at(px, py, c) = 0.5f + 0.3f * std::sin(0.3f * px + 0.2f * py + c);
        y.at(px, py, c) = 0.45f + 0.3f * std::sin(0.31f * px + 0.18f * py + c);
      }
    }
  }
  double ssim = 0, max_ref = 0;
  Image grad;
  ASSERT_TRUE(SsimZeroPadded(x, y, &ssim, &grad).ok());
  const double error = MaxGradientError(x, y, grad, &max_ref);
  EXPECT_LE(error, kGradientTolerance * max_ref);
}

// The threaded path at a size split across threads: sampled positions, borders included.
TEST(SsimTest, LargeImageGradientMatchesFiniteDifferences) {
  std::mt19937 rng(12);
  const Image x = RandomImage(160, 120, 3, &rng);
  const Image y = CorrelatedImage(x, &rng);
  double ssim = 0;
  Image grad;
  ASSERT_TRUE(SsimZeroPadded(x, y, &ssim, &grad).ok());
  const DoubleImage dx(x), dy(y);
  const int xs[] = {0, 3, 80, 156, 159}, ys[] = {0, 4, 60, 117, 119};
  double max_error = 0, max_ref = 0;
  for (int py : ys) {
    for (int px : xs) {
      for (int c = 0; c < 3; ++c) {
        const double numeric = SsimDerivative(dx, dy, px, py, c, 1e-5);
        max_error = std::max(max_error, std::fabs(grad.at(px, py, c) - numeric));
        max_ref = std::max(max_ref, std::fabs(numeric));
      }
    }
  }
  EXPECT_LE(max_error, kGradientTolerance * max_ref);
}

TEST(SsimTest, WorkspaceReuseGivesSameResults) {
  std::mt19937 rng(13);
  SsimWorkspace workspace;
  Image grad;
  const Shape shapes[] = {{32, 24, 3}, {17, 13, 1}, {32, 24, 3}};
  for (const Shape& s : shapes) {
    const Image x = RandomImage(s.width, s.height, s.channels, &rng);
    const Image y = CorrelatedImage(x, &rng);
    double reused = 0, fresh = 0, valid_reused = 0, valid_fresh = 0;
    Image fresh_grad;
    ASSERT_TRUE(SsimZeroPadded(x, y, &reused, &grad, &workspace).ok());
    ASSERT_TRUE(SsimZeroPadded(x, y, &fresh, &fresh_grad).ok());
    ASSERT_TRUE(SsimValid(x, y, &valid_reused, &workspace).ok());
    ASSERT_TRUE(SsimValid(x, y, &valid_fresh).ok());
    EXPECT_EQ(reused, fresh);
    EXPECT_EQ(valid_reused, valid_fresh);
    EXPECT_EQ(grad.pixels, fresh_grad.pixels);
  }
}

TEST(SsimTest, RejectsBadShapes) {
  double ssim = 0;
  EXPECT_EQ(SsimZeroPadded(Image(8, 8, 3), Image(8, 9, 3), &ssim).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(SsimZeroPadded(Image(8, 8, 3), Image(8, 8, 1), &ssim).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(SsimZeroPadded(Image(), Image(), &ssim).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(SsimValid(Image(10, 20, 1), Image(10, 20, 1), &ssim).code(), M4D_ERR_INVALID_ARG);
  Image broken(8, 8, 3);
  broken.pixels.pop_back();
  EXPECT_EQ(SsimZeroPadded(broken, Image(8, 8, 3), &ssim).code(), M4D_ERR_INVALID_ARG);
  // Small images are fine in the zero-padded convention.
  EXPECT_TRUE(SsimZeroPadded(Image(1, 1, 1, 0.5f), Image(1, 1, 1, 0.5f), &ssim).ok());
  EXPECT_NEAR(ssim, 1.0, 1e-6);
}

}  // namespace
}  // namespace m4d
