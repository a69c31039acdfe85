// Initial Gaussians from points (train/point_initialisation.h), the camera scene extent
// (train/scene_extent.h) and model conversions (train/gaussian_model.h).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/point_initialisation.h"
#include "encoder/src/train/scene_extent.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

TEST(PointInitialisationTest, ScalesColoursOpacityRotation) {
  // Points at x = 0, 1, 2, 3, 10: the first one's 3 neighbours are at squared distances
  // 1, 4, 9; the last one's at 49, 64, 81.
  PointCloud points;
  for (float x : {0.0f, 1.0f, 2.0f, 3.0f, 10.0f}) {
    points.positions.insert(points.positions.end(), {x, 0.0f, 0.0f});
    points.colors.insert(points.colors.end(), {x / 10.0f, 0.5f, 1.0f});
  }
  GaussianModel model;
  ASSERT_TRUE(InitialiseFromPoints(points, PointInitialisationOptions(), &model).ok());
  ASSERT_EQ(model.size(), 5u);
  EXPECT_EQ(model.sh_degree, 3);
  EXPECT_FLOAT_EQ(model.log_scales[0], 0.5f * std::log(14.0f / 3.0f));
  EXPECT_FLOAT_EQ(model.log_scales[2], model.log_scales[0]);    // isotropic
  EXPECT_FLOAT_EQ(model.log_scales[3], 0.5f * std::log(2.0f));  // x = 1: 1, 1, 4
  EXPECT_FLOAT_EQ(model.log_scales[12], 0.5f * std::log(194.0f / 3.0f));
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(model.rotations[4 * i], 1.0f);
    EXPECT_EQ(model.rotations[4 * i + 1], 0.0f);
    EXPECT_NEAR(1.0f / (1.0f + std::exp(-model.opacity_logits[i])), 0.1f, 1e-6f);
    EXPECT_EQ(model.positions[3 * i], points.positions[3 * i]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(0.5f + kShC0 * model.sh[48 * i + c], points.colors[3 * i + c], 1e-6f);
    }
    for (int j = 3; j < 48; ++j) EXPECT_EQ(model.sh[48 * i + j], 0.0f);
  }
}

TEST(PointInitialisationTest, DuplicatesGetTheMinimumDistance) {
  PointCloud points;
  points.positions = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  points.colors.assign(12, 0.5f);
  GaussianModel model;
  ASSERT_TRUE(InitialiseFromPoints(points, PointInitialisationOptions(), &model).ok());
  EXPECT_FLOAT_EQ(model.log_scales[0], 0.5f * std::log(1e-7f));
}

TEST(PointInitialisationTest, BadInputIsRejected) {
  GaussianModel model;
  PointCloud points;
  points.positions = {0, 0, 0, 1, 1, 1};
  points.colors = {0, 0, 0};
  EXPECT_EQ(InitialiseFromPoints(points, PointInitialisationOptions(), &model).code(),
            M4D_ERR_INVALID_ARG);
  points.colors = {0, 0, 0, 0, 0, 0};
  points.positions[4] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(InitialiseFromPoints(points, PointInitialisationOptions(), &model).code(),
            M4D_ERR_INVALID_ARG);
  PointInitialisationOptions bad;
  bad.opacity = 1.0f;
  points.positions[4] = 1;
  EXPECT_EQ(InitialiseFromPoints(points, bad, &model).code(), M4D_ERR_INVALID_ARG);
}

TEST(SceneExtentTest, ReferenceRadiusOfCameraCentres) {
  std::vector<Camera> cameras;
  const float target[3] = {0, 0, 0};
  for (float x : {-2.0f, 2.0f, 0.0f}) {
    const float eye[3] = {x + 1.0f, 0.0f, -3.0f};
    cameras.push_back(test::LookAtCamera(64, 48, 60, 0, 0, eye, target));
  }
  const SceneBounds bounds = CameraSceneBounds(cameras);
  EXPECT_NEAR(bounds.centre[0], 1.0f, 1e-5f);
  EXPECT_NEAR(bounds.centre[2], -3.0f, 1e-5f);
  EXPECT_NEAR(bounds.extent, 2.2f, 1e-5f);
  EXPECT_EQ(CameraSceneBounds({cameras[0]}).extent, 0.0f);
}

TEST(GaussianModelTest, ConvertsToAndFromGaussianSets) {
  test::SceneOptions scene;
  scene.count = 7;
  scene.sh_degree = 1;
  const GaussianSet set = test::RandomGaussians(scene, 3);
  GaussianModel model;
  ASSERT_TRUE(ModelFromGaussianSet(set, 3, &model).ok());
  ASSERT_EQ(model.size(), 7u);
  EXPECT_EQ(model.sh[48 * 2 + 11], set.sh[12 * 2 + 11]);
  EXPECT_EQ(model.sh[48 * 2 + 12], 0.0f);
  GaussianSet back;
  ASSERT_TRUE(ModelToGaussianSet(model, 1, &back).ok());
  EXPECT_EQ(back.sh_degree, 1);
  EXPECT_TRUE(std::equal(back.sh.begin(), back.sh.end(), set.sh.begin()));
  EXPECT_TRUE(std::equal(back.positions.begin(), back.positions.end(), set.positions.begin()));
  EXPECT_TRUE(std::equal(back.rotations.begin(), back.rotations.end(), set.rotations.begin()));
  GaussianSet dc;
  ASSERT_TRUE(ModelToGaussianSet(model, 0, &dc).ok());
  EXPECT_EQ(dc.sh[3 * 4 + 2], set.sh[12 * 4 + 2]);
  GaussianModel low;
  ASSERT_TRUE(ModelFromGaussianSet(set, 0, &low).ok());
  EXPECT_EQ(ModelToGaussianSet(low, 2, &back).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ModelFromGaussianSet(set, 4, &model).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
