// Bjontegaard deltas (metrics/bjontegaard.h) against values worked out independently:
// curves whose differences are known in closed form, and a general case integrated
// numerically (Simpson's rule on 200k intervals over the same PCHIP curves) in a separate
// script rather than with the analytic integral under test.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "encoder/src/metrics/bjontegaard.h"

namespace m4d {
namespace {

const std::vector<RatePoint> kAnchor = {{100, 30.0}, {200, 33.1}, {400, 35.8}, {800, 37.9}};

TEST(Bjontegaard, IdenticalCurvesDiffer0) {
  BjontegaardDelta d;
  ASSERT_TRUE(ComputeBjontegaard(kAnchor, kAnchor, &d).ok());
  EXPECT_NEAR(d.rate_percent, 0.0, 1e-9);
  EXPECT_NEAR(d.psnr_db, 0.0, 1e-9);
}

// Every rate times 0.9 at the same PSNR: log-rate shifts by log10(0.9) everywhere, so
// BD-rate is exactly -10%, and the order of the points given does not matter.
TEST(Bjontegaard, ScaledRatesGiveTheScale) {
  std::vector<RatePoint> test;
  for (auto it = kAnchor.rbegin(); it != kAnchor.rend(); ++it)
    test.push_back({0.9 * it->rate, it->psnr});
  BjontegaardDelta d;
  ASSERT_TRUE(ComputeBjontegaard(kAnchor, test, &d).ok());
  EXPECT_NEAR(d.rate_percent, -10.0, 1e-9);
  EXPECT_GT(d.psnr_db, 0.0);
}

// PSNR = 30 + 10 log10(rate / 100) against 31 + 10 log10(rate / 100): straight lines, which
// PCHIP reproduces, 1 dB apart; for equal PSNR the test needs 10^-0.1 of the rate.
TEST(Bjontegaard, ParallelLinesInLogRate) {
  std::vector<RatePoint> anchor, test;
  for (double r : {100.0, 150.0, 300.0, 500.0, 1000.0}) {
    anchor.push_back({r, 30 + 10 * std::log10(r / 100)});
    test.push_back({r, 31 + 10 * std::log10(r / 100)});
  }
  BjontegaardDelta d;
  ASSERT_TRUE(ComputeBjontegaard(anchor, test, &d).ok());
  EXPECT_NEAR(d.psnr_db, 1.0, 1e-9);
  EXPECT_NEAR(d.rate_percent, (std::pow(10.0, -0.1) - 1) * 100, 1e-9);  // -20.567%
}

TEST(Bjontegaard, GeneralCurvesMatchNumericalIntegration) {
  const std::vector<RatePoint> test = {{90, 30.2}, {170, 33.0}, {330, 35.9}, {700, 38.3}};
  BjontegaardDelta d;
  ASSERT_TRUE(ComputeBjontegaard(kAnchor, test, &d).ok());
  EXPECT_NEAR(d.rate_percent, -16.4927587, 1e-5);
  EXPECT_NEAR(d.psnr_db, 0.7092521, 1e-6);
  // Swapping the curves reverses the sign of BD-PSNR.
  BjontegaardDelta back;
  ASSERT_TRUE(ComputeBjontegaard(test, kAnchor, &back).ok());
  EXPECT_NEAR(back.psnr_db, -d.psnr_db, 1e-9);
}

// A test curve much cheaper than the anchor: the PSNR ranges overlap (34 to 40 dB) but the
// rates do not (20 to 80 against 100 to 1000), so there is a BD-rate and no BD-PSNR. Lines
// 11 dB apart at 10 dB per decade: equal PSNR at 10^-1.1 of the rate.
TEST(Bjontegaard, RateWithoutACommonRateRange) {
  std::vector<RatePoint> anchor, test;
  for (double r : {100.0, 200.0, 500.0, 1000.0})
    anchor.push_back({r, 30 + 10 * std::log10(r / 100)});
  for (double r : {20.0, 40.0, 80.0}) test.push_back({r, 41 + 10 * std::log10(r / 100)});
  BjontegaardDelta d;
  ASSERT_TRUE(ComputeBjontegaard(anchor, test, &d).ok());
  EXPECT_TRUE(d.has_rate);
  EXPECT_FALSE(d.has_psnr);
  EXPECT_NEAR(d.rate_percent, (std::pow(10.0, -1.1) - 1) * 100, 1e-9);  // -92.06%
  ASSERT_TRUE(ComputeBjontegaard(test, anchor, &d).ok());
  EXPECT_NEAR(d.rate_percent, (std::pow(10.0, 1.1) - 1) * 100, 1e-7);
}

TEST(Bjontegaard, RejectsUnusableCurves) {
  BjontegaardDelta d;
  EXPECT_EQ(ComputeBjontegaard({{100, 30}}, kAnchor, &d).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ComputeBjontegaard({{0, 30}, {100, 31}}, kAnchor, &d).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ComputeBjontegaard({{100, 31}, {200, 30}}, kAnchor, &d).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ComputeBjontegaard({{100, NAN}, {200, 30}}, kAnchor, &d).code(), M4D_ERR_INVALID_ARG);
  // No common PSNR or rate range.
  EXPECT_EQ(ComputeBjontegaard({{1000, 40}, {2000, 41}}, kAnchor, &d).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
