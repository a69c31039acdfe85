// Background shell (background_shell.h): the sphere of a ring of inward-looking cameras is the
// ring's, and its points carry the colour the views see there.
#include <gtest/gtest.h>

#include <cmath>

#include "encoder/src/train/background_shell.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

TrainingViews Ring(int count, float distance, float height_centre) {
  TrainingViews views;
  const float target[3] = {0.0f, height_centre, 0.0f};
  for (int c = 0; c < count; ++c) {
    const float angle = 6.2831853f * static_cast<float>(c) / static_cast<float>(count);
    const float eye[3] = {distance * std::sin(angle), height_centre + 0.3f * (c % 2),
                          distance * std::cos(angle)};
    views.cameras.push_back(test::LookAtCamera(32, 24, 30.0f, 0, 0, eye, target));
    Image image(32, 24, 3);
    for (float& v : image.pixels) v = 0.25f;
    views.images.push_back(image);
  }
  return views;
}

TEST(BackgroundShellTest, TheSphereOfAnInwardRing) {
  const TrainingViews views = Ring(8, 4.0f, 1.0f);
  const BackgroundShell shell = CameraShell(views, 1.0f);
  EXPECT_NEAR(shell.centre[0], 0.0f, 0.05f);
  EXPECT_NEAR(shell.centre[1], 1.0f, 0.2f);
  EXPECT_NEAR(shell.centre[2], 0.0f, 0.05f);
  EXPECT_NEAR(shell.radius, 4.0f, 0.1f);
  BackgroundShellOptions options;
  options.points = 2000;
  PointCloud points;
  ASSERT_TRUE(BackgroundShellPoints(views, options, &points).ok());
  ASSERT_GT(points.size(), 50u);
  EXPECT_LT(points.size(), 2000u);  // the poles no two cameras see are dropped
  for (size_t i = 0; i < points.size(); ++i) {
    const float* p = &points.positions[3 * i];
    const float r =
        std::sqrt(p[0] * p[0] + (p[1] - shell.centre[1]) * (p[1] - shell.centre[1]) + p[2] * p[2]);
    EXPECT_NEAR(r, shell.radius, 0.2f);
    EXPECT_FLOAT_EQ(points.colors[3 * i], 0.25f);
  }
}

TEST(BackgroundShellTest, ParallelCamerasGiveNoShell) {
  TrainingViews views;
  for (int c = 0; c < 3; ++c) {
    const float eye[3] = {static_cast<float>(c), 0.0f, -4.0f};
    const float target[3] = {static_cast<float>(c), 0.0f, 0.0f};
    views.cameras.push_back(test::LookAtCamera(32, 24, 30.0f, 0, 0, eye, target));
    views.images.emplace_back(32, 24, 3);
  }
  PointCloud points;
  ASSERT_TRUE(BackgroundShellPoints(views, BackgroundShellOptions(), &points).ok());
  EXPECT_EQ(points.size(), 0u);
  BackgroundShellOptions bad;
  bad.radius_scale = 0;
  EXPECT_EQ(BackgroundShellPoints(views, bad, &points).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
