#include "encoder/src/train/camera_colour.h"

#include <gtest/gtest.h>

#include <cmath>

namespace m4d {
namespace {

// Two views of the same grey ramp, one camera brighter and bluer than the other: the terms
// learn the difference, split around the cameras' mean (what both share stays with the model).
TEST(CameraColourTest, LearnsEachViewsGainAndOffsetAroundTheirMean) {
  constexpr int kPixels = 64;
  const float gain[2] = {1.1f, 1.0f / 1.1f}, offset[2] = {0.03f, -0.03f};
  CameraColour colour;
  colour.Init(2, 2e-3f);
  ASSERT_TRUE(colour.enabled());
  for (int step = 0; step < 3000; ++step) {
    const int view = step % 2;
    Image render, gradient;
    Reshape(kPixels, 1, 3, &render);
    Reshape(kPixels, 1, 3, &gradient);
    for (int p = 0; p < kPixels; ++p) {
      for (int c = 0; c < 3; ++c) render.pixels[3 * p + c] = 0.2f + 0.6f * p / kPixels;
    }
    Image raw = render;
    colour.Apply(view, &render);
    for (size_t i = 0; i < render.pixels.size(); ++i) {
      const float blue = i % 3 == 2 ? offset[view] : 0.0f;
      const float target = gain[view] * raw.pixels[i] + blue;
      gradient.pixels[i] = 2.0f * (render.pixels[i] - target) / kPixels;
    }
    colour.Backward(view, render, &gradient);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(colour.terms(0)[c], std::log(1.1f), 0.01) << c;
    EXPECT_NEAR(colour.terms(1)[c], -std::log(1.1f), 0.01) << c;
    EXPECT_NEAR(colour.terms(0)[c] + colour.terms(1)[c], 0.0f, 1e-6f);
  }
  EXPECT_NEAR(colour.terms(0)[5], 0.03f, 0.01);
  EXPECT_NEAR(colour.terms(1)[5], -0.03f, 0.01);
  EXPECT_NEAR(colour.terms(0)[3], 0.0f, 0.01);
}

}  // namespace
}  // namespace m4d
