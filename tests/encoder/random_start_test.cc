// Random start (random_start.h): points where two views look, coloured from them; the box's
// rest only when the views see almost none of it.
#include <gtest/gtest.h>

#include <cmath>

#include "encoder/src/train/random_start.h"
#include "encoder/src/train/view_sampling.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

// Two cameras 4 units in front of the origin, each image one flat colour.
TrainingViews TwoViews() {
  TrainingViews views;
  const float target[3] = {0.0f, 0.0f, 0.0f};
  for (int c = 0; c < 2; ++c) {
    const float eye[3] = {c == 0 ? -1.0f : 1.0f, 0.0f, -4.0f};
    views.cameras.push_back(test::LookAtCamera(32, 24, 30.0f, 0, 0, eye, target));
    Image image(32, 24, 3);
    for (float& v : image.pixels) v = c == 0 ? 0.2f : 0.6f;
    views.images.push_back(image);
  }
  return views;
}

int ViewsSeeing(const TrainingViews& views, const float* p) {
  int seen = 0;
  for (int v = 0; v < views.size(); ++v) {
    float rgb[3];
    seen += SampleView(views.cameras[v], views.images[v], p, rgb) ? 1 : 0;
  }
  return seen;
}

TEST(RandomStartTest, PointsWhereBothViewsLookWithTheirMeanColour) {
  const TrainingViews views = TwoViews();
  const float lo[3] = {-6, -6, -6}, hi[3] = {6, 6, 6};
  RandomStartOptions options;
  options.points = 500;
  options.seed = 3;
  PointCloud a, b;
  ASSERT_TRUE(ViewedRandomPoints(views, lo, hi, options, &a).ok());
  ASSERT_TRUE(ViewedRandomPoints(views, lo, hi, options, &b).ok());
  ASSERT_EQ(a.size(), 500u);
  EXPECT_EQ(a.positions, b.positions);  // seeded
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(ViewsSeeing(views, &a.positions[3 * i]), 2);
    EXPECT_FLOAT_EQ(a.colors[3 * i], 0.4f);
  }
}

TEST(RandomStartTest, FillsTheBoxWhereTheViewsSeeNone) {
  const TrainingViews views = TwoViews();
  const float lo[3] = {-3, -3, -9}, hi[3] = {3, 3, -8};  // behind both cameras
  RandomStartOptions options;
  options.points = 50;
  options.max_draws_per_point = 2;
  PointCloud points;
  ASSERT_TRUE(ViewedRandomPoints(views, lo, hi, options, &points).ok());
  ASSERT_EQ(points.size(), 50u);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_GE(points.positions[3 * i + 2], -9.0f);
    EXPECT_LE(points.positions[3 * i + 2], -8.0f);
    EXPECT_FLOAT_EQ(points.colors[3 * i], 0.5f);
  }
  const float bad[3] = {1, 1, NAN};
  EXPECT_EQ(ViewedRandomPoints(views, lo, bad, options, &points).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
