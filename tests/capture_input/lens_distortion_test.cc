// Lens distortion models (dataset/lens_distortion.h) and undistortion to a pinhole camera
// (dataset/undistortion.h): OpenCV's formulas at hand-computed points, forward and inverse
// round trips, the valid region of the pinhole camera, bilinear remapping and refusals.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "encoder/src/dataset/lens_distortion.h"
#include "encoder/src/dataset/undistortion.h"
#include "encoder/src/image/image.h"
#include "sdk/src/render/camera.h"

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

Camera TestCamera(int width, int height, double fx, double fy) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = static_cast<float>(fx);
  camera.fy = static_cast<float>(fy);
  camera.cx = static_cast<float>(0.5 * width + 1.3);
  camera.cy = static_cast<float>(0.5 * height - 2.2);
  camera.translation[2] = 3;
  return camera;
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

TEST(UndistortionTest, PinholeCameraKeepsOnlyValidPixelsAndAllOfThem) {
  const Camera distorted = TestCamera(200, 150, 160, 158);
  for (const LensDistortion& lens : RealisticLenses()) {
    const std::string name = LensModelName(lens.model);
    Camera pinhole;
    Status status = UndistortedCamera(distorted, lens, "test", &pinhole);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(pinhole.width, distorted.width);
    EXPECT_EQ(pinhole.height, distorted.height);
    EXPECT_EQ(pinhole.translation[2], distorted.translation[2]);
    // The field of view changes, by tens of percent at most for these lenses.
    EXPECT_GT(pinhole.fx, 0.7 * distorted.fx) << name;
    EXPECT_LT(pinhole.fx, 1.4 * distorted.fx) << name;
    EXPECT_GT(pinhole.fy, 0.7 * distorted.fy) << name;
    EXPECT_LT(pinhole.fy, 1.4 * distorted.fy) << name;
    EXPECT_NE(pinhole.fx, distorted.fx) << name;
    UndistortionMap map;
    status = BuildUndistortionMap(distorted, lens, pinhole, "test", &map);
    ASSERT_TRUE(status.ok()) << status.message();
    ASSERT_EQ(map.source.size(), 2u * 200 * 150);
    // Every pixel samples inside the source image (pixel centres 0 .. width - 1), and the
    // pinhole image reaches each of its four edges (alpha 0 keeps the largest rectangle).
    float low[2] = {1e9f, 1e9f}, high[2] = {-1e9f, -1e9f};
    for (size_t p = 0; p < map.source.size(); p += 2) {
      for (int a = 0; a < 2; ++a) {
        low[a] = std::min(low[a], map.source[p + a]);
        high[a] = std::max(high[a], map.source[p + a]);
      }
    }
    EXPECT_GE(low[0], 0) << name;
    EXPECT_GE(low[1], 0) << name;
    EXPECT_LE(high[0], 199) << name;
    EXPECT_LE(high[1], 149) << name;
    EXPECT_LT(low[0], 0.1) << name;
    EXPECT_LT(low[1], 0.1) << name;
    EXPECT_GT(high[0], 198.9) << name;
    EXPECT_GT(high[1], 148.9) << name;
  }
}

TEST(UndistortionTest, ZeroCoefficientsLeaveTheCamera) {
  const Camera distorted = TestCamera(64, 48, 50, 52);
  for (LensModel model : {LensModel::kNone, LensModel::kOpenCv, LensModel::kFisheye}) {
    const LensDistortion lens = Lens(model, {});
    EXPECT_FALSE(HasDistortion(lens));
    Camera pinhole;
    ASSERT_TRUE(UndistortedCamera(distorted, lens, "test", &pinhole).ok());
    EXPECT_EQ(pinhole.fx, distorted.fx);
    EXPECT_EQ(pinhole.fy, distorted.fy);
    EXPECT_EQ(pinhole.cx, distorted.cx);
    EXPECT_EQ(pinhole.cy, distorted.cy);
  }
  EXPECT_TRUE(HasDistortion(Lens(LensModel::kOpenCv, {}, 0, 1e-9)));
}

TEST(UndistortionTest, RemapInterpolatesBilinearly) {
  const Camera distorted = TestCamera(40, 30, 35, 35);
  const LensDistortion lens = Lens(LensModel::kOpenCv, {0.1, -0.05}, 0.002, 0.001);
  Camera pinhole;
  UndistortionMap map;
  ASSERT_TRUE(UndistortedCamera(distorted, lens, "test", &pinhole).ok());
  ASSERT_TRUE(BuildUndistortionMap(distorted, lens, pinhole, "test", &map).ok());
  // Linear in column and row per channel: bilinear interpolation reproduces it exactly.
  Image source(40, 30, 3);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      for (int c = 0; c < 3; ++c) source.at(x, y, c) = 0.01f * x * (c + 1) + 0.02f * y - 0.1f * c;
    }
  }
  Image out;
  ASSERT_TRUE(Remap(map, source, &out).ok());
  ASSERT_EQ(out.width, 40);
  ASSERT_EQ(out.height, 30);
  ASSERT_EQ(out.channels, 3);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      const float* s = &map.source[2 * (static_cast<size_t>(y) * 40 + x)];
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(out.at(x, y, c), 0.01f * s[0] * (c + 1) + 0.02f * s[1] - 0.1f * c, 1e-5);
      }
    }
  }
  EXPECT_EQ(Remap(map, Image(41, 30, 3), &out).code(), M4D_ERR_INVALID_ARG);
}

TEST(UndistortionTest, RefusesNonFiniteAndTooStrongDistortion) {
  const Camera distorted = TestCamera(160, 120, 130, 130);
  Camera pinhole;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const LensDistortion& lens :
       {Lens(LensModel::kOpenCv, {nan}), Lens(LensModel::kOpenCv, {}, 0, inf),
        Lens(LensModel::kFisheye, {0, 0, 0, -inf})}) {
    const Status status = UndistortedCamera(distorted, lens, "camera 'left'", &pinhole);
    EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
    EXPECT_NE(status.message().find("camera 'left'"), std::string::npos) << status.message();
  }
  // k1 = -0.9 folds over at normalised radius 0.61, inside the image (edges at 0.62 and
  // more), as do tangential terms of 0.5; huge coefficients would zoom in or out by orders of
  // magnitude. A fisheye of focal 40 sees more than 90 degrees off axis at the image edges.
  for (const LensDistortion& lens :
       {Lens(LensModel::kRadial, {-0.9}), Lens(LensModel::kOpenCv, {0.1}, 0.5, 0.5),
        Lens(LensModel::kRadial, {1e30}), Lens(LensModel::kFullOpenCv, {0, 0, 0, 1e6})}) {
    const Status status = UndistortedCamera(distorted, lens, "camera 'left'", &pinhole);
    EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED) << LensModelName(lens.model);
    EXPECT_NE(status.message().find("camera 'left'"), std::string::npos) << status.message();
  }
  const Status status = UndistortedCamera(TestCamera(160, 120, 40, 40),
                                          Lens(LensModel::kFisheye, {0.01}), "cam 7", &pinhole);
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("cam 7"), std::string::npos) << status.message();
  // Intrinsics the loader would reject later are refused before any undistortion.
  Camera bad = distorted;
  bad.fx = 0;
  EXPECT_EQ(UndistortedCamera(bad, Lens(LensModel::kRadial, {0.1}), "x", &pinhole).code(),
            M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
