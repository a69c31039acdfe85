// PNG reading and writing (encoder/src/image_io/png_io.h). Fixtures for the colour types and bit
// depths the writer does not produce are built here byte by byte (stored deflate blocks), so the
// reader is checked against the format itself rather than against libpng's writer.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/png_io.h"
#include "sdk/src/common/crc32.h"
#include "tests/encoder/image_test_util.h"

namespace m4d {
namespace {

using testing::PutBigEndian32;
using testing::TempFile;

constexpr int kGray = 0, kRgb = 2, kPalette = 3, kGrayAlpha = 4, kRgba = 6;

void AppendChunk(const char* type, const std::vector<uint8_t>& data, std::vector<uint8_t>* png) {
  PutBigEndian32(static_cast<uint32_t>(data.size()), png);
  std::vector<uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png->insert(png->end(), body.begin(), body.end());
  PutBigEndian32(Crc32(body.data(), body.size()), png);
}

// A zlib stream of stored (uncompressed) deflate blocks.
std::vector<uint8_t> ZlibStored(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> z = {0x78, 0x01};
  size_t pos = 0;
  do {
    const size_t len = std::min<size_t>(raw.size() - pos, 65535);
    const bool last = pos + len == raw.size();
    z.push_back(last ? 1 : 0);
    z.push_back(static_cast<uint8_t>(len));
    z.push_back(static_cast<uint8_t>(len >> 8));
    z.push_back(static_cast<uint8_t>(~len));
    z.push_back(static_cast<uint8_t>(~len >> 8));
    z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + len);
    pos += len;
  } while (pos < raw.size());
  uint32_t a = 1, b = 0;  // Adler-32
  for (uint8_t v : raw) {
    a = (a + v) % 65521;
    b = (b + a) % 65521;
  }
  PutBigEndian32((b << 16) | a, &z);
  return z;
}

struct PngFixture {
  uint32_t width = 0, height = 0;
  int bit_depth = 8, color_type = kRgb;
  std::vector<uint8_t> rows;  // packed samples of each row, without the filter byte
  std::vector<uint8_t> palette, transparency;
};

std::vector<uint8_t> MakePng(const PngFixture& f) {
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> ihdr;
  PutBigEndian32(f.width, &ihdr);
  PutBigEndian32(f.height, &ihdr);
  ihdr.insert(ihdr.end(),
              {static_cast<uint8_t>(f.bit_depth), static_cast<uint8_t>(f.color_type), 0, 0, 0});
  AppendChunk("IHDR", ihdr, &png);
  if (!f.palette.empty()) AppendChunk("PLTE", f.palette, &png);
  if (!f.transparency.empty()) AppendChunk("tRNS", f.transparency, &png);
  std::vector<uint8_t> raw;
  const size_t row_bytes = f.height ? f.rows.size() / f.height : 0;
  for (uint32_t y = 0; y < f.height; ++y) {
    raw.push_back(0);  // filter: none
    raw.insert(raw.end(), f.rows.begin() + y * row_bytes, f.rows.begin() + (y + 1) * row_bytes);
  }
  AppendChunk("IDAT", ZlibStored(raw), &png);
  AppendChunk("IEND", {}, &png);
  return png;
}

Status Decode(const std::vector<uint8_t>& bytes, Image* image) {
  return DecodePng(bytes.data(), bytes.size(), image);
}

void ExpectShape(const Image& image, int width, int height, int channels) {
  EXPECT_EQ(image.width, width);
  EXPECT_EQ(image.height, height);
  EXPECT_EQ(image.channels, channels);
  EXPECT_EQ(image.pixels.size(), static_cast<size_t>(width) * height * channels);
}

Image RandomByteImage(int width, int height, int channels, std::mt19937* rng) {
  Image image(width, height, channels);
  for (float& v : image.pixels) v = ByteToFloat(static_cast<uint8_t>((*rng)() & 0xff));
  return image;
}

TEST(PngIoTest, EightBitRoundTripIsExact) {
  std::mt19937 rng(31);
  for (int channels : {1, 3, 4}) {
    const Image in = RandomByteImage(37, 21, channels, &rng);
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(EncodePng(in, &bytes).ok());
    Image out;
    ASSERT_TRUE(Decode(bytes, &out).ok());
    ExpectShape(out, 37, 21, channels);
    EXPECT_EQ(out.pixels, in.pixels) << channels << " channels";

    const TempFile file("round_trip_" + std::to_string(channels) + ".png");
    ASSERT_TRUE(WritePng(file.path(), in).ok());
    Image from_file;
    ASSERT_TRUE(ReadPng(file.path(), &from_file).ok());
    EXPECT_EQ(from_file.pixels, in.pixels);
  }
}

TEST(PngIoTest, WriteRoundsAndClamps) {
  Image in(6, 1, 1);
  in.pixels = {-0.5f, 0.5f, 1.5f, std::numeric_limits<float>::quiet_NaN(), 0.2f / 255, 0.6f / 255};
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodePng(in, &bytes).ok());
  Image out;
  ASSERT_TRUE(Decode(bytes, &out).ok());
  const uint8_t expected[] = {0, 128, 255, 0, 0, 1};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(out.pixels[i], ByteToFloat(expected[i])) << i;
}

TEST(PngIoTest, ReadsSixteenBitRgb) {
  PngFixture f;
  f.width = 3;
  f.height = 2;
  f.bit_depth = 16;
  f.color_type = kRgb;
  const uint16_t samples[18] = {0,     65535, 0x1234, 1,     2,     3,    40000, 50000, 60000,
                                65534, 32768, 257,    12345, 54321, 9999, 7,     8,     9};
  for (uint16_t s : samples) f.rows.insert(f.rows.end(), {uint8_t(s >> 8), uint8_t(s & 0xff)});
  Image out;
  ASSERT_TRUE(Decode(MakePng(f), &out).ok());
  ExpectShape(out, 3, 2, 3);
  for (int i = 0; i < 18; ++i) EXPECT_EQ(out.pixels[i], samples[i] / 65535.0f) << i;
}

TEST(PngIoTest, SixteenBitGrayAlphaBecomesRgba) {
  PngFixture f;
  f.width = 2;
  f.height = 1;
  f.bit_depth = 16;
  f.color_type = kGrayAlpha;
  f.rows = {0x80, 0x00, 0xff, 0xff, 0x00, 0x10, 0x00, 0x00};  // (32768, 65535), (16, 0)
  Image out;
  ASSERT_TRUE(Decode(MakePng(f), &out).ok());
  ExpectShape(out, 2, 1, 4);
  const float g0 = 32768 / 65535.0f, g1 = 16 / 65535.0f;
  const std::vector<float> expected = {g0, g0, g0, 1.0f, g1, g1, g1, 0.0f};
  EXPECT_EQ(out.pixels, expected);
}

TEST(PngIoTest, PaletteExpandsToRgbOrRgba) {
  PngFixture f;
  f.width = 4;
  f.height = 1;
  f.bit_depth = 2;  // 4 indices in one byte: 3, 0, 1, 2
  f.color_type = kPalette;
  f.rows = {0b11000110};
  f.palette = {10, 20, 30, 40, 50, 60, 70, 80, 90, 255, 0, 128};
  Image rgb;
  ASSERT_TRUE(Decode(MakePng(f), &rgb).ok());
  ExpectShape(rgb, 4, 1, 3);
  const int indices[4] = {3, 0, 1, 2};
  for (int x = 0; x < 4; ++x) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(rgb.at(x, 0, c), ByteToFloat(f.palette[3 * indices[x] + c]));
    }
  }
  f.transparency = {0, 100};  // entries 0 and 1; the others stay opaque
  Image rgba;
  ASSERT_TRUE(Decode(MakePng(f), &rgba).ok());
  ExpectShape(rgba, 4, 1, 4);
  const float alpha[4] = {1.0f, 0.0f, ByteToFloat(100), 1.0f};
  for (int x = 0; x < 4; ++x) EXPECT_EQ(rgba.at(x, 0, 3), alpha[x]) << x;
  EXPECT_EQ(rgba.at(0, 0, 0), ByteToFloat(255));
}

TEST(PngIoTest, LowBitDepthGrayScalesToUnitRange) {
  PngFixture f;
  f.width = 8;
  f.height = 2;
  f.bit_depth = 1;
  f.color_type = kGray;
  f.rows = {0b10110000, 0b00000001};
  Image bits;
  ASSERT_TRUE(Decode(MakePng(f), &bits).ok());
  ExpectShape(bits, 8, 2, 1);
  const std::vector<float> expected = {1, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
  EXPECT_EQ(bits.pixels, expected);

  f.width = 2;
  f.height = 1;
  f.bit_depth = 4;
  f.rows = {0x5f};  // 5 and 15: 4-bit samples scale by 17
  Image nibbles;
  ASSERT_TRUE(Decode(MakePng(f), &nibbles).ok());
  EXPECT_EQ(nibbles.pixels, (std::vector<float>{ByteToFloat(85), 1.0f}));
}

TEST(PngIoTest, GrayTransparencyBecomesRgba) {
  PngFixture f;
  f.width = 2;
  f.height = 1;
  f.bit_depth = 8;
  f.color_type = kGray;
  f.rows = {7, 200};
  f.transparency = {0, 7};  // gray 7 is transparent
  Image out;
  ASSERT_TRUE(Decode(MakePng(f), &out).ok());
  ExpectShape(out, 2, 1, 4);
  const float g0 = ByteToFloat(7), g1 = ByteToFloat(200);
  EXPECT_EQ(out.pixels, (std::vector<float>{g0, g0, g0, 0.0f, g1, g1, g1, 1.0f}));
}

std::vector<uint8_t> SmallRgbaPng() {
  PngFixture f;
  f.width = 5;
  f.height = 4;
  f.color_type = kRgba;
  for (int i = 0; i < 5 * 4 * 4; ++i) f.rows.push_back(static_cast<uint8_t>(i * 3));
  return MakePng(f);
}

TEST(PngIoTest, FixtureDecodes) {
  Image out;
  ASSERT_TRUE(Decode(SmallRgbaPng(), &out).ok());
  ExpectShape(out, 5, 4, 4);
  EXPECT_EQ(out.pixels[10], ByteToFloat(30));
}

TEST(PngIoTest, EveryTruncationIsAnError) {
  const std::vector<uint8_t> png = SmallRgbaPng();
  for (size_t size = 0; size < png.size(); ++size) {
    const std::vector<uint8_t> cut(png.begin(), png.begin() + size);  // exact size: no overread
    Image out;
    const Status status = Decode(cut, &out);
    EXPECT_EQ(status.code(), size < 8 ? M4D_ERR_UNSUPPORTED : M4D_ERR_BITSTREAM) << size;
  }
}

TEST(PngIoTest, CorruptDataIsAnError) {
  const std::vector<uint8_t> png = SmallRgbaPng();
  Image out;
  // A bit flipped in the IHDR data: the chunk CRC no longer matches.
  std::vector<uint8_t> bad_crc = png;
  bad_crc[16] ^= 0x40;
  EXPECT_EQ(Decode(bad_crc, &out).code(), M4D_ERR_BITSTREAM);
  // Not a PNG at all.
  const std::vector<uint8_t> text = {'h', 'e', 'l', 'l', 'o', ' ', 'p', 'n', 'g', '!'};
  EXPECT_EQ(Decode(text, &out).code(), M4D_ERR_UNSUPPORTED);
  // A valid container around a broken zlib stream (bad header check bits).
  PngFixture f;
  f.width = 1;
  f.height = 1;
  f.color_type = kGray;
  f.rows = {9};
  std::vector<uint8_t> broken = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> ihdr;
  PutBigEndian32(1, &ihdr);
  PutBigEndian32(1, &ihdr);
  ihdr.insert(ihdr.end(), {8, 0, 0, 0, 0});
  AppendChunk("IHDR", ihdr, &broken);
  AppendChunk("IDAT", {0x78, 0x02, 0xff, 0xff, 0xff, 0xff}, &broken);
  AppendChunk("IEND", {}, &broken);
  EXPECT_EQ(Decode(broken, &out).code(), M4D_ERR_BITSTREAM);
  // Zero width is invalid in IHDR.
  f.width = 0;
  EXPECT_EQ(Decode(MakePng(f), &out).code(), M4D_ERR_BITSTREAM);
}

TEST(PngIoTest, AbsurdDimensionsAreRejectedBeforeDecoding) {
  // A 60000 x 60000 RGBA header with a few bytes of data: refused from the header alone.
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<uint8_t> ihdr;
  PutBigEndian32(60000, &ihdr);
  PutBigEndian32(60000, &ihdr);
  ihdr.insert(ihdr.end(), {8, kRgba, 0, 0, 0});
  AppendChunk("IHDR", ihdr, &png);
  AppendChunk("IDAT", ZlibStored({0, 1, 2, 3}), &png);
  AppendChunk("IEND", {}, &png);
  Image out;
  const Status status = Decode(png, &out);
  EXPECT_EQ(status.code(), M4D_ERR_LIMIT) << status.message();
  EXPECT_NE(status.message().find("60000"), std::string::npos) << status.message();
}

TEST(PngIoTest, FileErrors) {
  Image out;
  const TempFile missing("missing.png");
  const Status status = ReadPng(missing.path(), &out);
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(status.message().find(missing.path()), std::string::npos) << status.message();

  const std::vector<uint8_t> png = SmallRgbaPng();
  const TempFile truncated("truncated.png", std::vector<uint8_t>(png.begin(), png.end() - 20));
  EXPECT_EQ(ReadPng(truncated.path(), &out).code(), M4D_ERR_BITSTREAM);

  EXPECT_EQ(WritePng(testing::TempPath("no/such/dir.png"), Image(2, 2, 3)).code(),
            M4D_ERR_INVALID_ARG);
}

TEST(PngIoTest, WriteRejectsInvalidImages) {
  std::vector<uint8_t> bytes;
  EXPECT_EQ(EncodePng(Image(), &bytes).code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(EncodePng(Image(3, 3, 2), &bytes).code(), M4D_ERR_INVALID_ARG);
  Image short_pixels(3, 3, 3);
  short_pixels.pixels.resize(5);
  EXPECT_EQ(EncodePng(short_pixels, &bytes).code(), M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
