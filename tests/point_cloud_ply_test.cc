// Binary PLY point clouds (dataset/point_cloud_ply.h): round trip, other vertex layouts,
// and malformed files.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "dataset/point_cloud_ply.h"
#include "image/byte_samples.h"
#include "image_test_util.h"

namespace m4d {
namespace {

std::vector<uint8_t> Bytes(const std::string& text) {
  return std::vector<uint8_t>(text.begin(), text.end());
}

void PutFloat(float v, std::vector<uint8_t>* out) {
  uint8_t b[4];
  std::memcpy(b, &v, 4);  // the test machines are little-endian, like the format
  out->insert(out->end(), b, b + 4);
}

TEST(PointCloudPly, RoundTripsPositionsAndByteColours) {
  PointCloud cloud;
  cloud.positions = {0.5f, -1.25f, 3.0f, 1e-3f, 2e5f, -7.5f};
  cloud.colors = {0.0f, 0.5f, 1.0f, ByteToFloat(17), ByteToFloat(200), 0.25f};
  testing::TempFile file("cloud.ply");
  ASSERT_TRUE(WritePointCloudPly(file.path(), cloud).ok());
  PointCloud read;
  ASSERT_TRUE(ReadPointCloudPly(file.path(), &read).ok());
  EXPECT_EQ(read.positions, cloud.positions);
  ASSERT_EQ(read.colors.size(), 6u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(FloatToByte(read.colors[i]), FloatToByte(cloud.colors[i]));
  }
}

TEST(PointCloudPly, ReadsOtherPropertiesAndTrailingElements) {
  // Normals between position and colour, no colour in the second file, faces after.
  std::vector<uint8_t> ply = Bytes(
      "ply\nformat binary_little_endian 1.0\ncomment made by hand\nelement vertex 1\n"
      "property float x\nproperty float y\nproperty float z\nproperty double nx\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face 0\nproperty list uchar int vertex_indices\nend_header\n");
  PutFloat(1, &ply);
  PutFloat(2, &ply);
  PutFloat(3, &ply);
  ply.insert(ply.end(), 8, 0);
  ply.insert(ply.end(), {255, 0, 51});
  PointCloud cloud;
  ASSERT_TRUE(DecodePointCloudPly(ply.data(), ply.size(), &cloud).ok());
  EXPECT_EQ(cloud.positions, (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(cloud.colors, (std::vector<float>{1.0f, 0.0f, 0.2f}));

  std::vector<uint8_t> plain = Bytes(
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n");
  PutFloat(4, &plain);
  PutFloat(5, &plain);
  PutFloat(6, &plain);
  ASSERT_TRUE(DecodePointCloudPly(plain.data(), plain.size(), &cloud).ok());
  EXPECT_EQ(cloud.colors, (std::vector<float>{0.5f, 0.5f, 0.5f}));
}

TEST(PointCloudPly, RejectsMalformedFiles) {
  PointCloud cloud;
  const auto decode = [&cloud](const std::vector<uint8_t>& bytes) {
    return DecodePointCloudPly(bytes.data(), bytes.size(), &cloud).code();
  };
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  EXPECT_EQ(decode(Bytes("not a ply")), M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(decode(Bytes("ply\nformat ascii 1.0\nelement vertex 1\n" + xyz + "end_header\n")),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(decode(Bytes("ply\nformat binary_little_endian 1.0\nelement vertex 1\n" + xyz)),
            M4D_ERR_BITSTREAM);
  // A billion vertices declared: refused before allocating anything.
  EXPECT_EQ(decode(Bytes("ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n" + xyz +
                         "end_header\n")),
            M4D_ERR_LIMIT);
  // Declares more vertices than the file holds.
  std::vector<uint8_t> short_file =
      Bytes("ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz + "end_header\n");
  short_file.resize(short_file.size() + 20);
  EXPECT_EQ(decode(short_file), M4D_ERR_BITSTREAM);
  EXPECT_EQ(decode(Bytes("ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                         "property double x\nproperty double y\nproperty double z\nend_header\n")),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(decode(Bytes("ply\nformat binary_little_endian 1.0\nelement face 1\n"
                         "property list uchar int i\nelement vertex 1\n" +
                         xyz + "end_header\n")),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(ReadPointCloudPly(::testing::TempDir() + "m4d_no_such.ply", &cloud).code(),
            M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
