// JPEG reading and writing (encoder/src/image_io/jpeg_io.h).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/metrics/psnr.h"
#include "tests/encoder/image_test_util.h"

namespace m4d {
namespace {

using testing::TempFile;

// Smooth shading with some texture: what photographs of a scene look like to JPEG.
Image TestPicture(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) {
        image.at(x, y, c) = 0.5f + 0.3f * std::sin(0.11f * x + 0.07f * y + 2.0f * c) +
                            0.1f * std::sin(0.5f * x + c) * std::cos(0.4f * y);
      }
    }
  }
  return image;
}

// At quality 95 without chroma subsampling the test picture comes back above this PSNR.
constexpr double kMinPsnrAt95 = 40.0;

TEST(JpegIoTest, RoundTripAtQuality95) {
  for (int channels : {3, 1}) {
    const Image in = TestPicture(64, 48, channels);
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(EncodeJpeg(in, 95, &bytes).ok());
    Image out;
    ASSERT_TRUE(DecodeJpeg(bytes.data(), bytes.size(), &out).ok());
    ASSERT_EQ(out.width, 64);
    ASSERT_EQ(out.height, 48);
    ASSERT_EQ(out.channels, channels);
    double psnr = 0;
    ASSERT_TRUE(Psnr(in, out, &psnr).ok());
    EXPECT_GT(psnr, kMinPsnrAt95) << channels << " channels";

    // Lower quality: smaller and worse.
    std::vector<uint8_t> low;
    ASSERT_TRUE(EncodeJpeg(in, 20, &low).ok());
    Image low_out;
    ASSERT_TRUE(DecodeJpeg(low.data(), low.size(), &low_out).ok());
    double low_psnr = 0;
    ASSERT_TRUE(Psnr(in, low_out, &low_psnr).ok());
    EXPECT_LT(low.size(), bytes.size());
    EXPECT_LT(low_psnr, psnr - 3);
  }
}

// Colour detail at full resolution survives: chroma is not subsampled (4:2:0 would blur it).
TEST(JpegIoTest, KeepsFullResolutionChroma) {
  Image in(32, 32, 3, 0.0f);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) in.at(x, y, (x + y) % 2 == 0 ? 0 : 2) = 1.0f;  // red / blue
  }
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeJpeg(in, 95, &bytes).ok());
  Image out;
  ASSERT_TRUE(DecodeJpeg(bytes.data(), bytes.size(), &out).ok());
  double psnr = 0;
  ASSERT_TRUE(Psnr(in, out, &psnr).ok());
  EXPECT_GT(psnr, 25.0);
}

std::vector<uint8_t> SmallJpeg() {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(EncodeJpeg(TestPicture(40, 24, 3), 90, &bytes).ok());
  return bytes;
}

TEST(JpegIoTest, FileRoundTrip) {
  const Image in = TestPicture(40, 24, 3);
  const TempFile file("picture.jpg");
  ASSERT_TRUE(WriteJpeg(file.path(), in, 95).ok());
  Image out;
  ASSERT_TRUE(ReadJpeg(file.path(), &out).ok());
  double psnr = 0;
  ASSERT_TRUE(Psnr(in, out, &psnr).ok());
  EXPECT_GT(psnr, kMinPsnrAt95);
}

// libjpeg would fill a cut-off scan with gray and only warn; the reader refuses.
TEST(JpegIoTest, TruncationIsAnError) {
  const std::vector<uint8_t> jpeg = SmallJpeg();
  for (size_t size = 0; size + 2 < jpeg.size(); size += 7) {
    const std::vector<uint8_t> cut(jpeg.begin(), jpeg.begin() + size);  // exact size
    Image out;
    EXPECT_EQ(DecodeJpeg(cut.data(), cut.size(), &out).code(), M4D_ERR_BITSTREAM) << size;
  }
  // Only the end-of-image marker missing.
  Image out;
  EXPECT_EQ(DecodeJpeg(jpeg.data(), jpeg.size() - 2, &out).code(), M4D_ERR_BITSTREAM);
}

// Offset of the SOF0 marker (baseline frame header) in a JPEG stream.
size_t FindFrameHeader(const std::vector<uint8_t>& jpeg) {
  for (size_t i = 2; i + 1 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xff && jpeg[i + 1] == 0xc0) return i;
  }
  ADD_FAILURE() << "no SOF0 marker";
  return 0;
}

TEST(JpegIoTest, CorruptDataIsAnError) {
  Image out;
  const std::vector<uint8_t> text = {'n', 'o', 't', ' ', 'a', ' ', 'j', 'p', 'e', 'g'};
  EXPECT_EQ(DecodeJpeg(text.data(), text.size(), &out).code(), M4D_ERR_BITSTREAM);
  // A frame header with 0 components.
  std::vector<uint8_t> jpeg = SmallJpeg();
  jpeg[FindFrameHeader(jpeg) + 9] = 0;
  EXPECT_EQ(DecodeJpeg(jpeg.data(), jpeg.size(), &out).code(), M4D_ERR_BITSTREAM);
  // A frame header with sample precision 3.
  jpeg = SmallJpeg();
  jpeg[FindFrameHeader(jpeg) + 4] = 3;
  EXPECT_EQ(DecodeJpeg(jpeg.data(), jpeg.size(), &out).code(), M4D_ERR_BITSTREAM);
}

TEST(JpegIoTest, AbsurdDimensionsAreRejectedBeforeDecoding) {
  std::vector<uint8_t> jpeg = SmallJpeg();
  const size_t sof = FindFrameHeader(jpeg);
  // Marker, length (2), precision (1), then height and width, big-endian: 65000 x 65000.
  jpeg[sof + 5] = jpeg[sof + 7] = 0xfd;
  jpeg[sof + 6] = jpeg[sof + 8] = 0xe8;
  Image out;
  const Status status = DecodeJpeg(jpeg.data(), jpeg.size(), &out);
  EXPECT_EQ(status.code(), M4D_ERR_LIMIT) << status.message();
}

TEST(JpegIoTest, FileErrors) {
  Image out;
  const TempFile missing("missing.jpg");
  EXPECT_EQ(ReadJpeg(missing.path(), &out).code(), M4D_ERR_INVALID_ARG);
  const std::vector<uint8_t> jpeg = SmallJpeg();
  const TempFile truncated("truncated.jpg", std::vector<uint8_t>(jpeg.begin(), jpeg.end() - 40));
  const Status status = ReadJpeg(truncated.path(), &out);
  EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
  EXPECT_NE(status.message().find(truncated.path()), std::string::npos) << status.message();
}

TEST(JpegIoTest, WriteRejectsBadArguments) {
  std::vector<uint8_t> bytes;
  EXPECT_EQ(EncodeJpeg(Image(4, 4, 4), 90, &bytes).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(EncodeJpeg(Image(4, 4, 3), 0, &bytes).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(EncodeJpeg(Image(4, 4, 3), 101, &bytes).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(EncodeJpeg(Image(), 90, &bytes).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(EncodeJpeg(Image(70000, 1, 1), 90, &bytes).code(), M4D_ERR_INVALID_ARG);
  EXPECT_TRUE(EncodeJpeg(Image(4, 4, 3), 1, &bytes).ok());
  EXPECT_TRUE(EncodeJpeg(Image(4, 4, 3), 100, &bytes).ok());
}

}  // namespace
}  // namespace m4d
