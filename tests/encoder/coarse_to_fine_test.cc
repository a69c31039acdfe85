// Coarse-to-fine training views (coarse_to_fine.h): which level an iteration fits, the levels
// a view's size allows, and that a level's image and camera agree with each other.
#include <gtest/gtest.h>

#include "encoder/src/train/coarse_to_fine.h"
#include "encoder/src/train/view_sampling.h"

namespace m4d {
namespace {

TrainingViews OneView(int width, int height) {
  TrainingViews views;
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = static_cast<float>(width);
  camera.cx = 0.5f * static_cast<float>(width);
  camera.cy = 0.5f * static_cast<float>(height);
  Image image(width, height, 3);
  // Each 4x4 block holds its own colour, so that any level's pixel is one block's mean.
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c)
        image.at(x, y, c) = static_cast<float>((x / 4 + 7 * (y / 4) + c) % 5) / 4;
    }
  }
  views.camera_indices = {0};
  views.cameras = {camera};
  views.images = {image};
  return views;
}

TEST(CoarseToFineTest, TheWindowIsSplitEvenlyFromTheCoarsestLevel) {
  ViewPyramid pyramid;
  ASSERT_TRUE(pyramid.Build(OneView(256, 128), {2, 101}).ok());
  ASSERT_EQ(pyramid.levels(), 2);
  EXPECT_EQ(pyramid.At(1)->cameras[0].width, 64);
  EXPECT_EQ(pyramid.At(50)->cameras[0].width, 64);
  EXPECT_EQ(pyramid.At(51)->cameras[0].width, 128);
  EXPECT_EQ(pyramid.At(100)->cameras[0].width, 128);
  EXPECT_EQ(pyramid.At(101), nullptr);
  EXPECT_EQ(pyramid.At(5000), nullptr);
}

TEST(CoarseToFineTest, LevelsStopAtTheSmallestUsefulView) {
  ViewPyramid pyramid;
  // 48 / 4 = 12 rows is below kMinCoarseViewSide: only the half-size level is built, and the
  // window's coarsest part fits it too.
  ASSERT_TRUE(pyramid.Build(OneView(256, 48), {3, 31}).ok());
  EXPECT_EQ(pyramid.levels(), 1);
  EXPECT_EQ(pyramid.At(1)->cameras[0].height, 24);
  EXPECT_EQ(pyramid.At(30)->cameras[0].height, 24);
  ViewPyramid off;
  ASSERT_TRUE(off.Build(OneView(256, 96), {0, 100}).ok());
  EXPECT_EQ(off.At(1), nullptr);
}

TEST(CoarseToFineTest, ALevelsCameraSeesWhereItsImageShowsTheFullView) {
  const TrainingViews views = OneView(256, 128);
  ViewPyramid pyramid;
  ASSERT_TRUE(pyramid.Build(views, {2, 10}).ok());
  const TrainingViews& coarse = *pyramid.At(1);  // factor 4: each pixel is one 4x4 block
  // Points in front of the camera, projected into the centre of blocks of the full view.
  for (int block = 0; block < 6; ++block) {
    const float u = 4.0f * (3 + 7 * block) + 2.0f, v = 4.0f * (2 + 4 * block) + 2.0f;
    const Camera& full = views.cameras[0];
    const float p[3] = {(u - full.cx) / full.fx * 2.0f, (v - full.cy) / full.fy * 2.0f, 2.0f};
    float expected[3], seen[3];
    ASSERT_TRUE(SampleView(full, views.images[0], p, expected));
    ASSERT_TRUE(SampleView(coarse.cameras[0], coarse.images[0], p, seen));
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(seen[c], expected[c]) << block;
  }
}

TEST(CoarseToFineTest, BadSchedulesAreRefused) {
  ViewPyramid pyramid;
  EXPECT_EQ(pyramid.Build(OneView(64, 64), {-1, 10}).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(pyramid.Build(OneView(64, 64), {kMaxCoarseLevels + 1, 10}).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(pyramid.Build(OneView(64, 64), {1, -1}).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
