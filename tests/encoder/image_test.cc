// The image type's checks, RGB conversion, area resizing and format detection (image/).

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/image/area_resize.h"
#include "encoder/src/image/image.h"
#include "encoder/src/image/rgb_conversion.h"
#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/image_file.h"
#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/image_io/png_io.h"
#include "tests/encoder/image_test_util.h"

namespace m4d {
namespace {

using testing::TempFile;

TEST(ImageTest, ShapeChecks) {
  EXPECT_TRUE(CheckImageShape(4096, 4096, 4, "t").ok());  // exactly 2^28 bytes
  EXPECT_EQ(CheckImageShape(4097, 4096, 4, "t").code(), M4D_ERR_LIMIT);
  EXPECT_EQ(CheckImageShape(1 << 30, 1 << 30, 3, "t").code(), M4D_ERR_LIMIT);
  EXPECT_EQ(CheckImageShape(0, 5, 3, "t").code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(CheckImageShape(5, -1, 3, "t").code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(CheckImageShape(5, 5, 2, "t").code(), M4D_ERR_INVALID_ARG);
  EXPECT_TRUE(CheckSameShape(Image(3, 2, 1), Image(3, 2, 1), "t").ok());
  EXPECT_EQ(CheckSameShape(Image(3, 2, 1), Image(2, 3, 1), "t").code(), M4D_ERR_INVALID_ARG);
  const Image image(3, 2, 3, 0.25f);
  EXPECT_EQ(image.at(2, 1, 2), 0.25f);
  EXPECT_EQ(image.row(1), image.pixels.data() + 9);
}

TEST(ImageTest, ConvertToRgb) {
  const float background[3] = {0.0f, 0.5f, 1.0f};
  Image gray(2, 1, 1);
  gray.pixels = {0.25f, 0.75f};
  Image rgb;
  ASSERT_TRUE(ConvertToRgb(gray, background, &rgb).ok());
  EXPECT_EQ(rgb.channels, 3);
  EXPECT_EQ(rgb.pixels, (std::vector<float>{0.25f, 0.25f, 0.25f, 0.75f, 0.75f, 0.75f}));

  Image rgba(3, 1, 4);
  rgba.pixels = {1.0f, 1.0f, 1.0f, 1.0f,                    // opaque white
                 1.0f, 1.0f, 1.0f, 0.0f,                    // fully transparent: the background
                 0.2f, 0.4f, 0.6f, 0.5f};                   // half: the mean with the background
  ASSERT_TRUE(ConvertToRgb(rgba, background, &rgba).ok());  // in place
  EXPECT_EQ(rgba.channels, 3);
  const std::vector<float> expected = {1, 1, 1, 0.0f, 0.5f, 1.0f, 0.1f, 0.45f, 0.8f};
  ASSERT_EQ(rgba.pixels.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_FLOAT_EQ(rgba.pixels[i], expected[i]) << i;

  Image copy;
  ASSERT_TRUE(ConvertToRgb(rgb, background, &copy).ok());
  EXPECT_EQ(copy.pixels, rgb.pixels);
  EXPECT_EQ(ConvertToRgb(Image(), background, &copy).code(), M4D_ERR_INVALID_ARG);
}

TEST(AreaResizeTest, HalvingAveragesBlocks) {
  Image in(4, 4, 1);
  for (int i = 0; i < 16; ++i) in.pixels[i] = static_cast<float>(i);
  Image out;
  ASSERT_TRUE(ResizeArea(in, 2, 2, &out).ok());
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 2);
  // Block means of 0 1 / 4 5, 2 3 / 6 7, 8 9 / 12 13, 10 11 / 14 15.
  EXPECT_EQ(out.pixels, (std::vector<float>{2.5f, 4.5f, 10.5f, 12.5f}));
}

TEST(AreaResizeTest, IntegerFactorPerChannel) {
  Image in(6, 3, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 6; ++x) {
      for (int c = 0; c < 3; ++c) in.at(x, y, c) = static_cast<float>(100 * c + 10 * y + x);
    }
  }
  Image out;
  ASSERT_TRUE(ResizeArea(in, 2, 1, &out).ok());  // 3 x 3 blocks
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(out.at(0, 0, c), 100 * c + 10 + 1);
    EXPECT_FLOAT_EQ(out.at(1, 0, c), 100 * c + 10 + 4);
  }
}

TEST(AreaResizeTest, FractionalFactorWeightsPartialPixels) {
  Image in(3, 1, 1);
  in.pixels = {3.0f, 6.0f, 12.0f};
  Image out;
  // Factor 1.5: each output covers one whole pixel and half of the middle one.
  ASSERT_TRUE(ResizeArea(in, 2, 1, &out).ok());
  EXPECT_FLOAT_EQ(out.pixels[0], (3.0f + 0.5f * 6.0f) / 1.5f);
  EXPECT_FLOAT_EQ(out.pixels[1], (0.5f * 6.0f + 12.0f) / 1.5f);

  // Factor 2.5 in both directions on a 5 x 5 ramp in x: the outputs are the column means.
  Image ramp(5, 5, 1);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 5; ++x) ramp.at(x, y, 0) = static_cast<float>(x);
  }
  ASSERT_TRUE(ResizeArea(ramp, 2, 2, &out).ok());
  const float left = (0 + 1 + 0.5f * 2) / 2.5f, right = (0.5f * 2 + 3 + 4) / 2.5f;
  EXPECT_EQ(out.pixels.size(), 4u);
  for (int y = 0; y < 2; ++y) {
    EXPECT_FLOAT_EQ(out.at(0, y, 0), left);
    EXPECT_FLOAT_EQ(out.at(1, y, 0), right);
  }
}

TEST(AreaResizeTest, PreservesConstantsAndUpscalesByReplication) {
  const Image flat(37, 23, 3, 0.3f);
  Image out;
  ASSERT_TRUE(ResizeArea(flat, 10, 7, &out).ok());
  for (float v : out.pixels) EXPECT_NEAR(v, 0.3f, 1e-6f);

  Image two(2, 1, 1);
  two.pixels = {1.0f, 5.0f};
  ASSERT_TRUE(ResizeArea(two, 4, 1, &two).ok());  // in place
  EXPECT_EQ(two.pixels, (std::vector<float>{1.0f, 1.0f, 5.0f, 5.0f}));
}

TEST(AreaResizeTest, RejectsBadSizes) {
  Image out;
  EXPECT_EQ(ResizeArea(Image(4, 4, 3), 0, 2, &out).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ResizeArea(Image(), 2, 2, &out).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(ResizeArea(Image(4, 4, 3), 1 << 20, 1 << 20, &out).code(), M4D_ERR_LIMIT);
}

TEST(ImageFileTest, DetectsFormatFromContent) {
  const Image rgb(8, 8, 3, ByteToFloat(100));
  // Misleading names: the content decides.
  const TempFile png("really_png.jpg"), jpeg("really_jpeg.png");
  ASSERT_TRUE(WritePng(png.path(), rgb).ok());
  ASSERT_TRUE(WriteJpeg(jpeg.path(), rgb, 95).ok());
  Image out;
  ASSERT_TRUE(ReadImageFile(png.path(), &out).ok());
  EXPECT_EQ(out.pixels, rgb.pixels);
  ASSERT_TRUE(ReadImageFile(jpeg.path(), &out).ok());
  ASSERT_EQ(out.pixels.size(), rgb.pixels.size());
  for (float v : out.pixels) EXPECT_NEAR(v, ByteToFloat(100), 1.5f / 255);

  const TempFile bmp("image.bmp", {'B', 'M', 0x36, 0, 0, 0, 0, 0});
  EXPECT_EQ(ReadImageFile(bmp.path(), &out).code(), M4D_ERR_UNSUPPORTED);
  const TempFile empty("empty.png", {});
  EXPECT_EQ(ReadImageFile(empty.path(), &out).code(), M4D_ERR_UNSUPPORTED);
  const TempFile missing("missing.png");
  EXPECT_EQ(ReadImageFile(missing.path(), &out).code(), M4D_ERR_INVALID_ARG);
}

TEST(FileBytesTest, SizeLimitIsEnforcedWhileReading) {
  const TempFile file("bytes.bin", std::vector<uint8_t>(100000, 7));
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(ReadFileBytes(file.path(), 100000, &bytes).ok());
  EXPECT_EQ(bytes.size(), 100000u);
  EXPECT_EQ(ReadFileBytes(file.path(), 99999, &bytes).code(), M4D_ERR_LIMIT);
  EXPECT_TRUE(bytes.empty());
  // A directory opens but cannot be read.
  EXPECT_EQ(ReadFileBytes(::testing::TempDir(), 100, &bytes).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
