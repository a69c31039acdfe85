// PLY import and export (ply/): the de-facto 3DGS Gaussian layout, bit-exact round trips,
// files from other writers (property order, types, formats, extra data) and malformed input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "encoder/src/ply/ply_header.h"
#include "encoder/src/ply/point_cloud_ply.h"
#include "tests/encoder/image_test_util.h"

namespace m4d {
namespace {

using testing::TempFile;

GaussianSet RandomSet(size_t n, int degree, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 2.0f);
  GaussianSet set;
  set.sh_degree = degree;
  set.Resize(n);
  for (auto* buffer :
       {&set.positions, &set.log_scales, &set.rotations, &set.opacity_logits, &set.sh}) {
    for (float& v : *buffer) v = normal(rng);
  }
  if (n > 0) set.positions[0] = std::numeric_limits<float>::denorm_min();  // survives exactly
  return set;
}

void ExpectSameSet(const GaussianSet& a, const GaussianSet& b) {
  ASSERT_EQ(a.sh_degree, b.sh_degree);
  ASSERT_EQ(a.size(), b.size());
  auto same_bits = [](const Buffer<float>& x, const Buffer<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * 4) == 0;
  };
  EXPECT_TRUE(same_bits(a.positions, b.positions));
  EXPECT_TRUE(same_bits(a.log_scales, b.log_scales));
  EXPECT_TRUE(same_bits(a.rotations, b.rotations));
  EXPECT_TRUE(same_bits(a.opacity_logits, b.opacity_logits));
  EXPECT_TRUE(same_bits(a.sh, b.sh));
}

// The value of one named 3DGS property of Gaussian g, from the set (the reference for
// files written here by hand).
double PropertyValue(const GaussianSet& set, size_t g, const std::string& name) {
  const int rest = ShCoefficients(set.sh_degree) - 1;
  const float* sh = &set.sh[g * set.sh_floats()];
  auto index = [&name](const char* prefix) { return std::stoi(name.substr(std::strlen(prefix))); };
  if (name == "x" || name == "y" || name == "z") return set.positions[3 * g + (name[0] - 'x')];
  if (name.rfind("nx", 0) == 0 || name == "ny" || name == "nz") return 0.0;
  if (name.rfind("f_dc_", 0) == 0) return sh[index("f_dc_")];
  if (name.rfind("f_rest_", 0) == 0) {
    const int i = index("f_rest_");
    return sh[3 * (i % rest + 1) + i / rest];  // channel-major in the file
  }
  if (name == "opacity") return set.opacity_logits[g];
  if (name.rfind("scale_", 0) == 0) return set.log_scales[3 * g + index("scale_")];
  if (name.rfind("rot_", 0) == 0) return set.rotations[4 * g + index("rot_")];
  return 42.0;  // an extra property
}

struct Property {
  std::string name;
  PlyType type;
};

void PutValue(double v, PlyType type, bool big_endian, std::vector<uint8_t>* out) {
  uint8_t bytes[8];
  const int size = PlyTypeSize(type);
  if (type == PlyType::kFloat32) {
    const float f = static_cast<float>(v);
    std::memcpy(bytes, &f, 4);
  } else if (type == PlyType::kFloat64) {
    std::memcpy(bytes, &v, 8);
  } else if (type == PlyType::kUint8) {
    bytes[0] = static_cast<uint8_t>(v);
  } else {
    const int32_t i = static_cast<int32_t>(v);
    std::memcpy(bytes, &i, 4);
  }
  for (int i = 0; i < size; ++i) out->push_back(bytes[big_endian ? size - 1 - i : i]);
}

// A PLY of the set with the given vertex properties, preceded by an element "camera" with a
// list property (which readers must step over).
std::vector<uint8_t> HandWrittenPly(const GaussianSet& set, const std::vector<Property>& properties,
                                    PlyFormat format) {
  const char* format_name = format == PlyFormat::kAscii                ? "ascii"
                            : format == PlyFormat::kBinaryLittleEndian ? "binary_little_endian"
                                                                       : "binary_big_endian";
  std::string header = std::string("ply\nformat ") + format_name +
                       " 1.0\ncomment written by hand\nelement camera 2\n"
                       "property list uchar int ids\nproperty float focal\nelement vertex " +
                       std::to_string(set.size()) + "\n";
  for (const Property& p : properties) {
    header += std::string("property ") + PlyTypeName(p.type) + " " + p.name + "\n";
  }
  header += "end_header\n";
  std::vector<uint8_t> bytes(header.begin(), header.end());
  const bool big = format == PlyFormat::kBinaryBigEndian;
  if (format == PlyFormat::kAscii) {
    const std::string cameras = "3 1 2 3 0.5\n0 1.5\n";
    bytes.insert(bytes.end(), cameras.begin(), cameras.end());
    for (size_t g = 0; g < set.size(); ++g) {
      std::string line;
      for (const Property& p : properties) {
        char text[64];
        std::snprintf(text, sizeof(text), "%.9g ", PropertyValue(set, g, p.name));
        line += text;
      }
      line.back() = '\n';
      bytes.insert(bytes.end(), line.begin(), line.end());
    }
    return bytes;
  }
  for (int ids : {3, 0}) {
    PutValue(ids, PlyType::kUint8, big, &bytes);
    for (int i = 0; i < ids; ++i) PutValue(i, PlyType::kInt32, big, &bytes);
    PutValue(0.5, PlyType::kFloat32, big, &bytes);
  }
  for (size_t g = 0; g < set.size(); ++g) {
    for (const Property& p : properties)
      PutValue(PropertyValue(set, g, p.name), p.type, big, &bytes);
  }
  return bytes;
}

std::vector<std::string> StandardNames(int degree) {
  std::vector<std::string> names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int i = 0; i < 3 * (ShCoefficients(degree) - 1); ++i) {
    names.push_back("f_rest_" + std::to_string(i));
  }
  for (const char* name :
       {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) {
    names.push_back(name);
  }
  return names;
}

TEST(GaussianPlyTest, RoundTripIsBitExactForEveryDegree) {
  for (int degree = 0; degree <= 3; ++degree) {
    const GaussianSet set = RandomSet(37, degree, 11 + degree);
    TempFile file("set" + std::to_string(degree) + ".ply");
    ASSERT_TRUE(WriteGaussianPly(file.path(), set).ok());
    GaussianSet back;
    const Status status = ReadGaussianPly(file.path(), &back);
    ASSERT_TRUE(status.ok()) << status.message();
    ExpectSameSet(set, back);
  }
  GaussianSet empty;
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeGaussianPly(empty, &bytes).ok());
  GaussianSet back = RandomSet(3, 1, 1);
  ASSERT_TRUE(DecodeGaussianPly(bytes.data(), bytes.size(), &back).ok());
  EXPECT_EQ(back.size(), 0u);
  EXPECT_EQ(back.sh_degree, 0);
}

TEST(GaussianPlyTest, ExportWritesTheDeFactoLayout) {
  const GaussianSet set = RandomSet(5, 3, 3);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeGaussianPly(set, &bytes).ok());
  std::string expected = "ply\nformat binary_little_endian 1.0\nelement vertex 5\n";
  const std::vector<std::string> names = StandardNames(3);
  ASSERT_EQ(names.size(), 62u);
  for (const std::string& name : names) expected += "property float " + name + "\n";
  expected += "end_header\n";
  ASSERT_EQ(bytes.size(), expected.size() + 5 * 62 * 4);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + expected.size()), expected);
  // Every value where the layout puts it: normals zero, f_rest channel-major.
  for (size_t g = 0; g < 5; ++g) {
    for (size_t p = 0; p < names.size(); ++p) {
      float v;
      std::memcpy(&v, &bytes[expected.size() + 4 * (62 * g + p)], 4);
      EXPECT_EQ(v, static_cast<float>(PropertyValue(set, g, names[p]))) << names[p];
    }
  }
  // f_rest_1 is coefficient 2 of red; f_rest_15 coefficient 1 of green.
  float rest1, rest15;
  std::memcpy(&rest1, &bytes[expected.size() + 4 * (9 + 1)], 4);
  std::memcpy(&rest15, &bytes[expected.size() + 4 * (9 + 15)], 4);
  EXPECT_EQ(rest1, set.sh[3 * 2 + 0]);
  EXPECT_EQ(rest15, set.sh[3 * 1 + 1]);
}

TEST(GaussianPlyTest, ImportAcceptsAnyOrderTypesExtrasAndFormats) {
  for (int degree : {0, 2}) {
    const GaussianSet set = RandomSet(9, degree, 5);
    std::vector<std::string> names = StandardNames(degree);
    names.erase(names.begin() + 3, names.begin() + 6);  // normals are optional
    names.push_back("confidence");
    names.push_back("label");
    std::vector<int> order(names.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::shuffle(order.begin(), order.end(), std::mt19937(degree));
    std::vector<Property> properties;
    for (int i : order) {
      // Some values as double (converting back to float is exact), extras as integers.
      const std::string& name = names[i];
      const PlyType type = name == "confidence" ? PlyType::kUint8
                           : name == "label"    ? PlyType::kInt32
                           : name == "y" || name == "scale_1" || name == "f_dc_2"
                               ? PlyType::kFloat64
                               : PlyType::kFloat32;
      properties.push_back({name, type});
    }
    for (PlyFormat format :
         {PlyFormat::kBinaryLittleEndian, PlyFormat::kBinaryBigEndian, PlyFormat::kAscii}) {
      const std::vector<uint8_t> bytes = HandWrittenPly(set, properties, format);
      GaussianSet back;
      const Status status = DecodeGaussianPly(bytes.data(), bytes.size(), &back);
      ASSERT_TRUE(status.ok()) << status.message();
      ExpectSameSet(set, back);
    }
  }
}

TEST(GaussianPlyTest, RejectsTruncatedAndGarbageFiles) {
  const GaussianSet set = RandomSet(4, 1, 9);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeGaussianPly(set, &bytes).ok());
  GaussianSet back;
  for (size_t size = 0; size < bytes.size(); size += (size < 700 ? 1 : 13)) {
    const Status status = DecodeGaussianPly(bytes.data(), size, &back);
    EXPECT_FALSE(status.ok()) << size;
  }
  std::vector<uint8_t> garbage(1000);
  std::mt19937 rng(1);
  for (uint8_t& b : garbage) b = static_cast<uint8_t>(rng());
  EXPECT_EQ(DecodeGaussianPly(garbage.data(), garbage.size(), &back).code(), M4D_ERR_UNSUPPORTED);
  // Garbage after a valid header: binary data of the wrong length.
  std::vector<uint8_t> extra = bytes;
  extra.pop_back();
  EXPECT_EQ(DecodeGaussianPly(extra.data(), extra.size(), &back).code(), M4D_ERR_BITSTREAM);
  TempFile missing("missing.ply");
  EXPECT_EQ(ReadGaussianPly(missing.path(), &back).code(), M4D_ERR_INVALID_ARG);
}

std::vector<uint8_t> Text(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

Status DecodeText(const std::string& text) {
  GaussianSet set;
  const std::vector<uint8_t> bytes = Text(text);
  return DecodeGaussianPly(bytes.data(), bytes.size(), &set);
}

TEST(GaussianPlyTest, RejectsMalformedHeaders) {
  const std::string start = "ply\nformat binary_little_endian 1.0\n";
  std::string props;
  for (const std::string& name : StandardNames(0)) props += "property float " + name + "\n";
  // A count far beyond the data is refused before anything is allocated.
  EXPECT_EQ(DecodeText(start + "element vertex 99999999999\n" + props + "end_header\n").code(),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(
      DecodeText(start + "element vertex 123456789012345678901\n" + props + "end_header\n").code(),
      M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText(start + "element vertex -1\n" + props + "end_header\n").code(),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText(start + "element vertex 0\n" + props).code(), M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText("ply\nelement vertex 0\n" + props + "end_header\n").code(),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText("ply\nformat binary_little_endian 2.0\nend_header\n").code(),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(DecodeText(start + "element vertex 0\nproperty quad x\nend_header\n").code(),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText(start + "element vertex 0\nproperty float x\nproperty float x\nend_header\n")
                .code(),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText(start + "property float x\nend_header\n").code(), M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText(start + "bogus line\nend_header\n").code(), M4D_ERR_BITSTREAM);
  EXPECT_EQ(DecodeText(start + "element face 0\nend_header\n").code(), M4D_ERR_BITSTREAM);
  // Missing opacity; f_rest counts of no SH degree; a gap in the f_rest numbering.
  std::string no_opacity = props;
  no_opacity.erase(no_opacity.find("property float opacity\n"), 23);
  EXPECT_EQ(DecodeText(start + "element vertex 0\n" + no_opacity + "end_header\n").code(),
            M4D_ERR_BITSTREAM);
  std::string rest;
  for (int i = 0; i < 10; ++i) rest += "property float f_rest_" + std::to_string(i) + "\n";
  EXPECT_EQ(DecodeText(start + "element vertex 0\n" + props + rest + "end_header\n").code(),
            M4D_ERR_UNSUPPORTED);
  std::string gap;
  for (int i = 1; i <= 9; ++i) gap += "property float f_rest_" + std::to_string(i) + "\n";
  EXPECT_EQ(DecodeText(start + "element vertex 0\n" + props + gap + "end_header\n").code(),
            M4D_ERR_BITSTREAM);
  EXPECT_TRUE(DecodeText(start + "element vertex 0\n" + props + "end_header\n").ok());
  // The header limit.
  std::string huge = start;
  while (huge.size() < (2u << 20)) huge += "comment padding padding padding padding\n";
  EXPECT_EQ(DecodeText(huge).code(), M4D_ERR_LIMIT);
}

TEST(GaussianPlyTest, RejectsNonFiniteValues) {
  GaussianSet set = RandomSet(3, 0, 2);
  set.log_scales[4] = std::numeric_limits<float>::infinity();
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeGaussianPly(set, &bytes).ok());
  GaussianSet back;
  EXPECT_EQ(DecodeGaussianPly(bytes.data(), bytes.size(), &back).code(), M4D_ERR_BITSTREAM);
  set.sh.pop_back();
  EXPECT_EQ(EncodeGaussianPly(set, &bytes).code(), M4D_ERR_INVALID_ARG);
}

TEST(PointCloudPlyTest, RoundTripAndColourTypes) {
  PointCloud points;
  points.positions = {1, 2, 3, -4.5f, 0.25f, 1e-3f};
  points.colors = {0, 0.5f, 1, 20 / 255.0f, 40 / 255.0f, 1};
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodePointCloudPly(points, &bytes).ok());
  PointCloud back;
  ASSERT_TRUE(DecodePointCloudPly(bytes.data(), bytes.size(), &back).ok());
  EXPECT_EQ(back.positions, points.positions);
  ASSERT_EQ(back.colors.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(back.colors[i], points.colors[i], 0.5 / 255 + 1e-6) << i;

  // Double coordinates and float colours (taken as they are), ASCII.
  const std::vector<uint8_t> ascii = Text(
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
      "property double z\nproperty float red\nproperty float green\nproperty float blue\n"
      "end_header\n1 2 3 0.25 0.5 0.75\n4 5 6 1 0 0.5\n");
  ASSERT_TRUE(DecodePointCloudPly(ascii.data(), ascii.size(), &back).ok());
  EXPECT_EQ(back.positions, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(back.colors, (std::vector<float>{0.25f, 0.5f, 0.75f, 1, 0, 0.5f}));

  // No colours: grey.
  const std::vector<uint8_t> plain = Text(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n");
  ASSERT_TRUE(DecodePointCloudPly(plain.data(), plain.size(), &back).ok());
  EXPECT_EQ(back.colors, (std::vector<float>{0.5f, 0.5f, 0.5f}));

  const std::vector<uint8_t> no_z = Text(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "end_header\n1 2\n");
  EXPECT_EQ(DecodePointCloudPly(no_z.data(), no_z.size(), &back).code(), M4D_ERR_BITSTREAM);
  const std::vector<uint8_t> short_ascii = Text(
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n4 5\n");
  EXPECT_EQ(DecodePointCloudPly(short_ascii.data(), short_ascii.size(), &back).code(),
            M4D_ERR_BITSTREAM);
}

}  // namespace
}  // namespace m4d
