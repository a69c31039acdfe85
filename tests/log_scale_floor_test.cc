// The log-scale floor (log_scale_floor.h) and how the keyframe coder and trainer apply it.
#include "layers/log_scale_floor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "gaussian_set_test_util.h"
#include "layers/gaussian_set_writer.h"
#include "splat_test_scenes.h"

namespace m4d {
namespace {

// n cameras on an arc of a circle of radius r around the origin, looking at it (fy = 1.05 fx).
std::vector<Camera> Ring(int n, float radius, float focal, float arc = 6.2831853f) {
  std::vector<Camera> cameras;
  const float target[3] = {0, 0, 0};
  for (int c = 0; c < n; ++c) {
    const float angle = arc * static_cast<float>(c) / static_cast<float>(n);
    const float eye[3] = {radius * std::cos(angle), 0.1f, radius * std::sin(angle)};
    cameras.push_back(test::LookAtCamera(320, 240, focal, 0, 0, eye, target));
  }
  return cameras;
}

// The floor of cameras Ring() places at `radius` (0.1 above the target) with fy 1.05 x 300.
double RingFloor(double radius) {
  return std::log(kInvisibleAxisPixels * std::sqrt(radius * radius + 0.01) / 315.0);
}

TEST(LogScaleFloorTest, TenthOfAPixelAtTheRigsDistance) {
  const float floor = LogScaleFloor(Ring(8, 2.0f, 300.0f));
  EXPECT_NEAR(floor, RingFloor(2.0), 1e-4);
  EXPECT_NEAR(LogScaleFloor(Ring(8, 4.0f, 300.0f)), RingFloor(4.0), 1e-4);
  // Twice the focal length, half the scale.
  EXPECT_NEAR(LogScaleFloor(Ring(8, 2.0f, 600.0f)) - floor, -std::log(2.0), 1e-4);
}

// A frontal arc: the centres lie close together, the scene is where their axes meet.
TEST(LogScaleFloorTest, ArcLooksAtTheSceneNotItsCentres) {
  EXPECT_NEAR(LogScaleFloor(Ring(8, 2.0f, 300.0f, 1.0f)), RingFloor(2.0), 1e-4);
}

// Parallel axes meet nowhere: the centres' spread stands in for the depth.
TEST(LogScaleFloorTest, ParallelCamerasUseTheirSpread) {
  std::vector<Camera> cameras;
  for (int c = 0; c < 5; ++c) {
    const float eye[3] = {0.5f * static_cast<float>(c - 2), 0, 0};
    const float target[3] = {eye[0], 0, 10};
    cameras.push_back(test::LookAtCamera(320, 240, 300.0f, 0, 0, eye, target));
  }
  // Distances from the mean: 1, 0.5, 0, 0.5, 1; median 0.5.
  EXPECT_NEAR(LogScaleFloor(cameras), std::log(kInvisibleAxisPixels * 0.5 / 315.0), 1e-4);
}

TEST(LogScaleFloorTest, NoFloorWithoutADistance) {
  EXPECT_TRUE(std::isinf(LogScaleFloor({})));
  const std::vector<Camera> ring = Ring(4, 2.0f, 300.0f);
  EXPECT_TRUE(std::isinf(LogScaleFloor({ring[0]})));
  EXPECT_TRUE(std::isinf(LogScaleFloor({ring[1], ring[1], ring[1]})));
}

// Log scales spread over e^-16..e^-1: with the floor at -7, those below code as -7 and the rest
// on a range of 6 instead of 15, so they err less; the decoder reconstructs the same values.
TEST(LogScaleFloorTest, CoderClampsBelowTheFloorAndRefinesAbove) {
  testing::UniformFloats uniform(3);
  GaussianSet set = testing::ZeroSet(4000, 1);
  for (float& v : set.positions) v = uniform(-1, 1);
  for (float& v : set.log_scales) v = uniform(-16, -1);
  for (float& v : set.rotations) v = uniform(-1, 1);
  GaussianQuantization q;
  q.log_scale_bits = 5;
  double error[2] = {0, 0};
  for (int with_floor : {0, 1}) {
    if (with_floor) q.log_scale_floor = -7.0f;
    GaussianSet quantized = set, decoded;
    ASSERT_TRUE(QuantizeGaussianSet(q, &quantized).ok());
    ASSERT_TRUE(ReconstructGaussianSet(set, q, &decoded).ok());
    for (size_t i = 0; i < set.log_scales.size(); ++i) {
      const float v = set.log_scales[i], coded = quantized.log_scales[i];
      if (with_floor && v < -7.0f) {
        EXPECT_EQ(coded, -7.0f);
      } else if (v >= -7.0f) {
        error[with_floor] = std::max(error[with_floor], std::fabs(static_cast<double>(coded) - v));
      }
    }
    std::vector<float> a(quantized.log_scales.begin(), quantized.log_scales.end());
    std::vector<float> b(decoded.log_scales.begin(), decoded.log_scales.end());
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);  // the coding reorders Gaussians; the values are the same
  }
  EXPECT_LE(error[0], 0.5 * 15.0 / 31.0 * 1.001);
  EXPECT_LE(error[1], 0.5 * 6.0 / 31.0 * 1.001);
  EXPECT_GT(error[0], 0.5 * 6.0 / 31.0 * 1.001);
}

TEST(LogScaleFloorTest, AllBelowTheFloorIsConstant) {
  GaussianSet set = testing::ZeroSet(100, 0);
  for (size_t i = 0; i < set.log_scales.size(); ++i) set.log_scales[i] = -12.0f - 0.01f * i;
  GaussianQuantization q;
  q.log_scale_floor = -7.0f;
  GaussianSet quantized = set;
  ASSERT_TRUE(QuantizeGaussianSet(q, &quantized).ok());
  for (float v : quantized.log_scales) EXPECT_EQ(v, -7.0f);
  GaussianQuantization no_floor = q;
  no_floor.log_scale_floor = -std::numeric_limits<float>::infinity();
  EXPECT_LT(testing::WriteSet(set, q).size(), testing::WriteSet(set, no_floor).size());
}

}  // namespace
}  // namespace m4d
