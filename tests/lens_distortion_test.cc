// Lens distortion models (dataset/lens_distortion.h): OpenCV's formulas at hand-computed
// points, forward and inverse round trips, and points the inverse must refuse.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "dataset/lens_distortion.h"

namespace m4d {
namespace {

constexpr double kPi = 3.141592653589793;

LensDistortion Lens(LensModel model, std::vector<double> k, double p1 = 0, double p2 = 0) {
  LensDistortion lens;
  lens.model = model;
  std::copy(k.begin(), k.end(), lens.k);
  lens.p1 = p1;
  lens.p2 = p2;
  return lens;
}

// Calibrations of the strength real cameras have, one or two per model.
std::vector<LensDistortion> RealisticLenses() {
  return {Lens(LensModel::kRadial, {-0.08}),
          Lens(LensModel::kRadial, {-0.3, 0.08}),
          Lens(LensModel::kOpenCv, {0.13, -0.25}, 0.0012, -0.0008),
          Lens(LensModel::kOpenCv, {-0.28, 0.07, 0.01}, -0.002, 0.003),
          Lens(LensModel::kFullOpenCv, {0.2, -0.1, 0.02, 0.15, -0.05, 0.01}, 0.001, 0.002),
          Lens(LensModel::kFisheye, {0.06, -0.02, 0.01, -0.004}),
          Lens(LensModel::kFisheye, {-0.03, 0.004, 0, 0})};
}

TEST(LensDistortionTest, FormulasAtHandComputedPoints) {
  double xd, yd;
  Distort(Lens(LensModel::kRadial, {0.1}), 0.5, 0, &xd, &yd);  // 0.5 (1 + 0.1 * 0.25)
  EXPECT_NEAR(xd, 0.5125, 1e-15);
  EXPECT_EQ(yd, 0);
  // Tangential: xd = x + 2 p1 x y + p2 (r^2 + 2 x^2), yd = y + p1 (r^2 + 2 y^2) + 2 p2 x y.
  Distort(Lens(LensModel::kOpenCv, {}, 0.01, 0), 0.5, 0.2, &xd, &yd);
  EXPECT_NEAR(xd, 0.502, 1e-15);
  EXPECT_NEAR(yd, 0.2037, 1e-15);
  Distort(Lens(LensModel::kOpenCv, {}, 0, 0.02), 0.5, 0.2, &xd, &yd);
  EXPECT_NEAR(xd, 0.5158, 1e-15);
  EXPECT_NEAR(yd, 0.204, 1e-15);
  // Rational: k4 divides.
  Distort(Lens(LensModel::kFullOpenCv, {0, 0, 0, 0.1}), 0.5, 0, &xd, &yd);
  EXPECT_NEAR(xd, 0.5 / 1.025, 1e-15);
  // Fisheye: the angle theta = atan(r) is distorted, theta (1 + k1 theta^2).
  Distort(Lens(LensModel::kFisheye, {0.1}), 0, 1, &xd, &yd);
  EXPECT_EQ(xd, 0);
  EXPECT_NEAR(yd, kPi / 4 * (1 + 0.1 * kPi * kPi / 16), 1e-15);
  Distort(Lens(LensModel::kFisheye, {}), 0, 0, &xd, &yd);
  EXPECT_EQ(xd, 0);
  EXPECT_EQ(yd, 0);
}

TEST(LensDistortionTest, InverseRoundTripsEveryModel) {
  for (const LensDistortion& lens : RealisticLenses()) {
    // A disk where these lenses are one-to-one (OpenCV's first folds over at radius 1.03).
    const double extent = lens.model == LensModel::kFisheye ? 1.4 : 0.8;
    for (double y = -extent; y <= extent + 1e-9; y += extent / 8) {
      for (double x = -extent; x <= extent + 1e-9; x += extent / 8) {
        if (std::hypot(x, y) > extent + 1e-9) continue;
        double xd, yd, u, v;
        Distort(lens, x, y, &xd, &yd);
        ASSERT_TRUE(Undistort(lens, xd, yd, &u, &v)) << LensModelName(lens.model) << x << y;
        EXPECT_NEAR(u, x, 1e-6) << LensModelName(lens.model) << " at " << x << ", " << y;
        EXPECT_NEAR(v, y, 1e-6) << LensModelName(lens.model) << " at " << x << ", " << y;
        // And the other way round, from a distorted point.
        ASSERT_TRUE(Undistort(lens, x, y, &u, &v)) << LensModelName(lens.model) << x << y;
        Distort(lens, u, v, &xd, &yd);
        EXPECT_NEAR(xd, x, 1e-6) << LensModelName(lens.model) << " at " << x << ", " << y;
        EXPECT_NEAR(yd, y, 1e-6) << LensModelName(lens.model) << " at " << x << ", " << y;
      }
    }
  }
}

TEST(LensDistortionTest, InverseRefusesPointsNoUndistortedPointReaches) {
  double x, y;
  // k1 = -0.5: r (1 - 0.5 r^2) peaks at r = 1 / sqrt(1.5), distorted radius 0.544.
  const LensDistortion barrel = Lens(LensModel::kRadial, {-0.5});
  EXPECT_TRUE(Undistort(barrel, 0.3, 0.2, &x, &y));
  EXPECT_FALSE(Undistort(barrel, 0.6, 0, &x, &y));
  EXPECT_FALSE(Undistort(barrel, 0.0, -0.7, &x, &y));
  // An equidistant fisheye sees 90 degrees off axis at distorted radius pi / 2, which no
  // pinhole camera sees.
  const LensDistortion fisheye = Lens(LensModel::kFisheye, {});
  EXPECT_TRUE(Undistort(fisheye, 1.5, 0, &x, &y));
  EXPECT_NEAR(x, std::tan(1.5), 1e-6);
  EXPECT_FALSE(Undistort(fisheye, 0, kPi / 2 + 0.01, &x, &y));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(Undistort(Lens(LensModel::kOpenCv, {nan}), 0.1, 0.1, &x, &y));
  EXPECT_FALSE(Undistort(Lens(LensModel::kFisheye, {nan}), 0.1, 0.1, &x, &y));
}

}  // namespace
}  // namespace m4d
