// The training loss L = (1 - lambda) L1 + lambda (1 - SSIM) (metrics/photometric_loss.h)
// against central finite differences of a double-precision evaluation of its definition.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "encoder/src/metrics/photometric_loss.h"
#include "tests/encoder/ssim_reference.h"

namespace m4d {
namespace {

using testing::CorrelatedImage;
using testing::DoubleImage;
using testing::RandomImage;
using testing::ReferenceSsim;
using testing::SsimDerivative;

// Finite-difference step; samples of rendered and target differ by more, so that the L1
// term is differentiable over the whole step.
constexpr double kStep = 1e-5;

// Pushes target samples away from rendered ones by at least 1e-3.
void SeparateSamples(const Image& rendered, Image* target) {
  for (size_t i = 0; i < target->pixels.size(); ++i) {
    if (std::fabs(target->pixels[i] - rendered.pixels[i]) < 1e-3f) target->pixels[i] += 2e-3f;
  }
}

TEST(PhotometricLossTest, ValueMatchesDefinition) {
  std::mt19937 rng(21);
  const Image rendered = RandomImage(23, 17, 3, &rng);
  const Image target = CorrelatedImage(rendered, &rng);
  for (double lambda : {0.2, 0.0, 1.0, 0.5}) {
    PhotometricLoss loss(lambda);
    PhotometricLossValue value;
    ASSERT_TRUE(loss.Evaluate(rendered, target, &value).ok());
    double l1 = 0;
    for (size_t i = 0; i < rendered.pixels.size(); ++i) {
      l1 += std::fabs(static_cast<double>(rendered.pixels[i]) - target.pixels[i]);
    }
    l1 /= static_cast<double>(rendered.pixels.size());
    const double ssim = ReferenceSsim(DoubleImage(rendered), DoubleImage(target), false);
    EXPECT_NEAR(value.l1, l1, 1e-9);
    EXPECT_NEAR(value.ssim, ssim, 1e-6);
    EXPECT_NEAR(value.loss, (1 - lambda) * l1 + lambda * (1 - ssim), 1e-6);
  }
  EXPECT_EQ(PhotometricLoss().ssim_weight(), 0.2);
}

// max |analytic - numeric| <= 1e-4 * max |numeric| over every sample.
TEST(PhotometricLossTest, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(22);
  for (int channels : {1, 3}) {
    const Image rendered = RandomImage(17, 13, channels, &rng);
    Image target = CorrelatedImage(rendered, &rng);
    SeparateSamples(rendered, &target);
    const double lambda = 0.2;
    PhotometricLoss loss(lambda);
    PhotometricLossValue value;
    Image grad;
    ASSERT_TRUE(loss.Evaluate(rendered, target, &value, &grad).ok());
    ASSERT_EQ(grad.pixels.size(), rendered.pixels.size());

    const DoubleImage r(rendered), t(target);
    const double n = static_cast<double>(rendered.pixels.size());
    double max_error = 0, max_ref = 0;
    for (int py = 0; py < rendered.height; ++py) {
      for (int px = 0; px < rendered.width; ++px) {
        for (int c = 0; c < channels; ++c) {
          const double d = r.at(px, py, c) - t.at(px, py, c);
          const double l1 = (std::fabs(d + kStep) - std::fabs(d - kStep)) / (2 * kStep) / n;
          const double numeric =
              (1 - lambda) * l1 - lambda * SsimDerivative(r, t, px, py, c, kStep);
          max_error = std::max(max_error, std::fabs(grad.at(px, py, c) - numeric));
          max_ref = std::max(max_ref, std::fabs(numeric));
        }
      }
    }
    EXPECT_LE(max_error, 1e-4 * max_ref) << channels << " channels";
  }
}

// A few plain gradient steps must lower the loss: the gradient points uphill.
TEST(PhotometricLossTest, GradientDescentLowersLoss) {
  std::mt19937 rng(23);
  Image rendered = RandomImage(32, 24, 3, &rng);
  const Image target = CorrelatedImage(RandomImage(32, 24, 3, &rng), &rng);
  PhotometricLoss loss;
  PhotometricLossValue before, after;
  Image grad;
  ASSERT_TRUE(loss.Evaluate(rendered, target, &before, &grad).ok());
  for (int step = 0; step < 20; ++step) {
    for (size_t i = 0; i < rendered.pixels.size(); ++i) {
      rendered.pixels[i] -= 200.0f * grad.pixels[i];
    }
    ASSERT_TRUE(loss.Evaluate(rendered, target, &after, &grad).ok());
  }
  EXPECT_LT(after.loss, 0.25 * before.loss);
  EXPECT_GT(after.ssim, before.ssim);
  EXPECT_LT(after.l1, before.l1);
}

TEST(PhotometricLossTest, RejectsMismatchedShapes) {
  PhotometricLoss loss;
  PhotometricLossValue value;
  Image grad;
  EXPECT_EQ(loss.Evaluate(Image(8, 8, 3), Image(8, 8, 1), &value, &grad).code(),
            M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
