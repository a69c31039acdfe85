// PSNR with the render's colour fitted per channel (metrics/colour_fitted_psnr.h).

#include <gtest/gtest.h>

#include <cmath>

#include "encoder/src/metrics/colour_fitted_psnr.h"
#include "encoder/src/metrics/psnr.h"

namespace m4d {
namespace {

// Samples in (0.1, 0.7), varied in every channel.
Image Texture() {
  Image image(9, 6, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = 0.1f + 0.6f * static_cast<float>((i * 37) % 17) / 17.0f;
  }
  return image;
}

TEST(ColourFittedPsnrTest, AnotherCamerasGainAndOffsetAreFittedAway) {
  const Image render = Texture();
  Image truth = render;
  const float gain[3] = {1.4f, 0.9f, 1.1f}, offset[3] = {-0.1f, 0.05f, 0.0f};
  for (size_t i = 0; i < truth.pixels.size(); ++i) {
    truth.pixels[i] = gain[i % 3] * render.pixels[i] + offset[i % 3];
  }
  double plain = 0, fitted = 0;
  ASSERT_TRUE(Psnr(render, truth, &plain).ok());
  ASSERT_TRUE(ColourFittedPsnr(render, truth, &fitted).ok());
  EXPECT_LT(plain, 25.0);
  EXPECT_GT(fitted, 90.0);
}

TEST(ColourFittedPsnrTest, ContentErrorIsKept) {
  const Image render = Texture();
  Image truth = render;
  for (size_t i = 0; i < truth.pixels.size(); i += 7) truth.pixels[i] += 0.2f;
  double plain = 0, fitted = 0;
  ASSERT_TRUE(Psnr(render, truth, &plain).ok());
  ASSERT_TRUE(ColourFittedPsnr(render, truth, &fitted).ok());
  // The fit can only lower the squared error, and not much where the error is no colour.
  EXPECT_GE(fitted, plain);
  EXPECT_LT(fitted, plain + 1.0);
}

TEST(ColourFittedPsnrTest, ConstantRenderTakesTheTruthsMean) {
  const Image render(4, 4, 3, 0.5f);
  Image truth(4, 4, 3, 0.2f);
  for (size_t i = 0; i < truth.pixels.size(); i += 3) truth.pixels[i] = 0.8f;
  double fitted = 0;
  ASSERT_TRUE(ColourFittedPsnr(render, truth, &fitted).ok());
  EXPECT_TRUE(std::isinf(fitted));
}

TEST(ColourFittedPsnrTest, ShapesMustMatch) {
  double psnr = 0;
  EXPECT_FALSE(ColourFittedPsnr(Image(4, 4, 3), Image(4, 5, 3), &psnr).ok());
}

}  // namespace
}  // namespace m4d
