// gaussian_set() coding (bitstream-spec 5.4, 5.5): round trips through WriteGaussianSet and
// ReadGaussianSet, Draco streams the spec refuses (kd-tree), and malformed input, which
// must fail cleanly and never crash.
#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/expert_encode.h>
#include <draco/point_cloud/point_cloud.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/layers/rotation_symmetry.h"
#include "encoder/src/layers/smallest_three.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/layers/gaussian_set_reader.h"
#include "sdk/src/layers/octree_positions.h"
#include "sdk/src/layers/rotation_coding.h"
#include "tests/encoder/gaussian_set_test_util.h"

namespace m4d {
namespace {

GaussianSet RandomSet(size_t n, int sh_degree, uint32_t seed) {
  testing::UniformFloats uniform(seed);
  GaussianSet set = testing::ZeroSet(n, sh_degree);
  for (float& v : set.positions) v = uniform(-10, 10);
  for (float& v : set.log_scales) v = uniform(-7, -1);
  for (float& v : set.rotations) v = uniform(-1, 1);
  for (float& v : set.opacity_logits) v = uniform(-5, 5);
  const size_t k = static_cast<size_t>(set.sh_floats());
  for (size_t i = 0; i < set.sh.size(); ++i) {
    set.sh[i] = i % k < 3 ? uniform(-2, 2) : uniform(-0.5f, 0.5f);
  }
  return set;
}

// Opacity carries the Gaussian's index exactly (24 bits, index < 2^23), so that decoded
// Gaussians can be matched to the originals whatever order the coding chose.
GaussianQuantization WithIds(GaussianQuantization q) {
  q.opacity_bits = 24;
  return q;
}
void SetIds(GaussianSet* set) {
  for (size_t i = 0; i < set->size(); ++i) set->opacity_logits[i] = static_cast<float>(i);
}

// Component r of attribute group `group` of Gaussian i (const or not, as `set` is).
template <typename Set>
auto& Component(Set& set, int group, size_t i, int r) {
  const size_t k = static_cast<size_t>(set.sh_floats());
  switch (group) {
    case kGroupPosition:
      return set.positions[3 * i + r];
    case kGroupLogScale:
      return set.log_scales[3 * i + r];
    case kGroupRotation:
      return set.rotations[4 * i + r];
    case kGroupOpacity:
      return set.opacity_logits[i];
    case kGroupShDc:
      return set.sh[k * i + r];
    default:
      return set.sh[k * i + 3 + r];
  }
}

// The syntax of spec 5.4, read back independently of the reader.
struct ParsedGroup {
  int bits = 0;
  bool per_component = false;
  std::vector<float> min, step;
  size_t offset = 0;  // of the bits byte
  float Min(int r) const { return min[per_component ? r : 0]; }
  float Step(int r) const { return step[per_component ? r : 0]; }
};
struct ParsedSet {
  uint32_t count = 0;
  size_t groups_offset = 0;  // first byte after count
  std::vector<ParsedGroup> groups;
  size_t draco_size_offset = 0;
  bool octree = false;  // positions in octree_positions() (0.7)
  std::vector<uint8_t> draco;
};

constexpr RotationCoding kFour = RotationCoding::kFourComponents;
constexpr RotationCoding kThree = RotationCoding::kSmallestThree;

// Version 0.7's syntax with that rotation coding, whose attributes are all in Draco (0.8's
// adaptive attributes are tested in adaptive_attributes_test.cc): four components are 0.4's,
// without codebooks or octree positions.
GaussianSetSyntax SyntaxOf(RotationCoding rotation, bool octree = true) {
  GaussianSetSyntax syntax;
  syntax.rotation = rotation;
  syntax.codebooks = rotation == kThree;
  syntax.octree_positions = rotation == kThree && octree;
  syntax.adaptive_attributes = false;
  return syntax;
}

ParsedSet Parse(const std::vector<uint8_t>& bytes, int sh_degree, RotationCoding rotation = kThree,
                bool octree = true) {
  ParsedSet p;
  ByteReader r(bytes.data(), bytes.size());
  EXPECT_TRUE(r.ReadVarUint(&p.count));
  p.groups_offset = r.position();
  for (int group = 0; group < kNumGaussianGroups; ++group) {
    const int components = CodedGroupComponents(group, sh_degree, rotation);
    if (components == 0) continue;
    ParsedGroup g;
    g.offset = r.position();
    uint8_t bits = 0, per_component = 0;
    EXPECT_TRUE(r.ReadU8(&bits) && r.ReadU8(&per_component));
    g.bits = bits;
    g.per_component = per_component != 0;
    for (int i = 0; i < (g.per_component ? components : 1); ++i) {
      float min = 0, step = 0;
      EXPECT_TRUE(r.ReadFiniteF32(&min) && r.ReadFiniteF32(&step));
      g.min.push_back(min);
      g.step.push_back(step);
    }
    if (rotation == kThree) {
      uint32_t codebook_size = 1;
      EXPECT_TRUE(r.ReadVarUint(&codebook_size));
      EXPECT_EQ(codebook_size, 0u) << "Parse reads scalar groups only";
    }
    p.groups.push_back(g);
  }
  uint8_t flag = 0;
  if (SyntaxOf(rotation, octree).octree_positions && p.groups[0].bits > 0) {
    EXPECT_TRUE(r.ReadU8(&flag));
  }
  p.octree = flag != 0;
  if (flag) {  // 0.7: octree_positions() (spec 5.6)
    std::vector<uint32_t> q(3 * static_cast<size_t>(p.count));
    EXPECT_TRUE(
        ReadOctreePositions(&r, RansLayout::kInterleaved, p.count, p.groups[0].bits, q.data())
            .ok());
  }
  p.draco_size_offset = r.position();
  uint32_t size = 0;
  const uint8_t* data = nullptr;
  EXPECT_TRUE(r.ReadVarUint(&size) && r.ReadBytes(size, &data));
  EXPECT_EQ(r.remaining(), 0u);
  if (data != nullptr) p.draco.assign(data, data + size);
  return p;
}

// The set `bytes` with another count and Draco payload.
std::vector<uint8_t> Reassemble(const std::vector<uint8_t>& bytes, const ParsedSet& p,
                                uint32_t count, const std::vector<uint8_t>& draco) {
  std::vector<uint8_t> out;
  ByteWriter w(&out);
  w.WriteVarUint(count);
  w.WriteBytes(bytes.data() + p.groups_offset, p.draco_size_offset - p.groups_offset);
  w.WriteVarUint(static_cast<uint32_t>(draco.size()));
  w.WriteBytes(draco);
  return out;
}

// These tests are of the Draco payload: every set is written with 0.7's syntax, all attributes
// in Draco.
std::vector<uint8_t> WriteSet(const GaussianSet& set, GaussianQuantization q) {
  q.syntax.adaptive_attributes = false;
  return testing::WriteSet(set, q);
}

GaussianQuantization FourComponents(GaussianQuantization q) {
  q.syntax = SyntaxOf(kFour);
  return q;
}

// Version 0.6's syntax: positions are Draco's first attribute (for the Draco payload's tests).
GaussianQuantization PositionsInDraco(GaussianQuantization q = GaussianQuantization()) {
  q.syntax = SyntaxOf(kThree, false);
  return q;
}

Status Read(const std::vector<uint8_t>& bytes, int sh_degree, GaussianSet* out,
            uint32_t max_count = kMaxGaussiansPerSet, RotationCoding rotation = kThree,
            bool octree = true) {
  ByteReader r(bytes.data(), bytes.size());
  const Status status = ReadGaussianSet(&r, sh_degree, SyntaxOf(rotation, octree), max_count, out);
  if (status.ok()) {
    EXPECT_EQ(r.remaining(), 0u);
  }
  return status;
}

Status ReadPositionsInDraco(const std::vector<uint8_t>& bytes, int sh_degree, GaussianSet* out) {
  return Read(bytes, sh_degree, out, kMaxGaussiansPerSet, kThree, false);
}

// The spec formula, one IEEE operation per statement.
float Dequantize(float min, uint32_t q, float step) {
  const float product = static_cast<float>(q) * step;
  return min + product;
}
bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// The coded components of a set: its own values, except smallest-three rotations, which are
// the three components SplitSmallestThree keeps of the original Gaussian's quaternion, of the
// original (split) or of the decoded quaternion (the three other than the original's index).
struct CodedValues {
  const GaussianSet& set;
  RotationCoding rotation;
  std::vector<float> abc;  // of the original
  std::vector<int> index;  // of the original
  CodedValues(const GaussianSet& original, RotationCoding coding)
      : set(original), rotation(coding) {
    abc.resize(3 * original.size());
    const float* first = original.rotations.data();
    bool identical = true;
    for (size_t i = 0; i < original.size(); ++i) {
      const float* q = &original.rotations[4 * i];
      index.push_back(SplitSmallestThree(q, &abc[3 * i]));
      identical = identical && std::equal(q, q + 4, first);
    }
    if (identical) {  // one rotation for all is coded with index 0 (a constant group)
      for (size_t i = 0; i < original.size(); ++i) SplitAt(first, 0, &abc[3 * i]);
      index.assign(original.size(), 0);
    }
  }
  float Original(int group, size_t i, int r) const {
    if (group == kGroupRotation && rotation == kThree) return abc[3 * i + r];
    return Component(set, group, i, r);
  }
  float Decoded(const GaussianSet& decoded, int group, size_t j, size_t i, int r) const {
    if (group == kGroupRotation && rotation == kThree) {
      return decoded.rotations[4 * j + (r < index[i] ? r : r + 1)];
    }
    return Component(decoded, group, j, r);
  }
};

// Checks that `decoded` is `original` quantized as the header says: every value is the spec
// formula of some q < 2^bits, within step / 2 (plus f32 rounding) of the original Gaussian's;
// a smallest-three rotation's fourth component is the one the spec recovers.
void ExpectRoundTrip(const GaussianSet& original, const std::vector<uint8_t>& bytes,
                     const GaussianSet& decoded, RotationCoding rotation = kThree) {
  const ParsedSet p = Parse(bytes, original.sh_degree, rotation);
  const CodedValues coded(original, rotation);
  ASSERT_EQ(decoded.size(), original.size());
  ASSERT_EQ(decoded.sh_degree, original.sh_degree);
  std::vector<bool> seen(original.size());
  for (size_t j = 0; j < decoded.size(); ++j) {
    const size_t i = static_cast<size_t>(std::lround(decoded.opacity_logits[j]));
    ASSERT_LT(i, original.size());
    ASSERT_FALSE(seen[i]) << "Gaussian " << i << " decoded twice";
    seen[i] = true;
    if (rotation == kThree) {
      float composed[4];
      const int largest = p.groups[kGroupRotation].bits > 0 ? coded.index[i] : 0;
      float abc[3];
      for (int r = 0, k = 0; r < 4; ++r) {
        if (r != largest) abc[k++] = decoded.rotations[4 * j + r];
      }
      ComposeSmallestThree(abc, largest, composed);
      for (int r = 0; r < 4; ++r) ASSERT_TRUE(SameBits(composed[r], decoded.rotations[4 * j + r]));
    }
    int k = 0;
    for (int group = 0; group < kNumGaussianGroups; ++group) {
      const int components = CodedGroupComponents(group, original.sh_degree, rotation);
      if (components == 0) continue;
      const ParsedGroup& g = p.groups[k++];
      for (int r = 0; r < components; ++r) {
        const float v = coded.Decoded(decoded, group, j, i, r), min = g.Min(r), step = g.Step(r);
        uint32_t q = 0;
        if (g.bits > 0 && step > 0) {
          q = static_cast<uint32_t>(std::max(0.0, std::round((double(v) - min) / step)));
        }
        bool exact = false;
        for (uint32_t c = q > 0 ? q - 1 : 0; c <= q + 1 && c < (1u << g.bits); ++c) {
          exact = exact || SameBits(v, Dequantize(min, c, step));
        }
        ASSERT_TRUE(exact) << "group " << group << " component " << r << ": " << v;
        const float o = coded.Original(group, i, r);
        const float ulp = std::max({std::fabs(o), std::fabs(min), std::fabs(v)}) *
                          std::numeric_limits<float>::epsilon();
        ASSERT_LE(std::fabs(double(v) - o), 0.5 * step + 4 * ulp)
            << "group " << group << " component " << r;
      }
    }
  }
}

void RoundTrip(const GaussianSet& set, const GaussianQuantization& q) {
  const std::vector<uint8_t> bytes = WriteSet(set, q);
  GaussianSet decoded;
  const Status status =
      Read(bytes, set.sh_degree, &decoded, kMaxGaussiansPerSet, q.syntax.rotation);
  ASSERT_TRUE(status.ok()) << status.message();
  ExpectRoundTrip(set, bytes, decoded, q.syntax.rotation);
}

TEST(GaussianSetCodingTest, RoundTripsEveryShDegree) {
  for (int degree = 0; degree <= 3; ++degree) {
    SCOPED_TRACE(degree);
    GaussianSet set = RandomSet(3000, degree, 10 + degree);
    SetIds(&set);
    RoundTrip(set, WithIds(GaussianQuantization()));
    RoundTrip(set, WithIds(FourComponents(GaussianQuantization())));
  }
}

TEST(GaussianSetCodingTest, RoundTripsEveryBitWidthAndSpeed) {
  GaussianSet set = RandomSet(500, 2, 7);
  SetIds(&set);
  for (int bits : {1, 2, 7, 8, 9, 15, 16, 17, 23, 24}) {
    SCOPED_TRACE(bits);
    GaussianQuantization q;
    q.position_bits = q.log_scale_bits = q.rotation_bits = q.sh_dc_bits = q.sh_rest_bits = bits;
    q.draco_speed = bits % 11;
    RoundTrip(set, WithIds(q));
    RoundTrip(set, WithIds(FourComponents(q)));
  }
}

TEST(GaussianSetCodingTest, DefaultQuantizationRoundTrips) {
  // Without ids: compare each component's values as a multiset.
  // Four-component rotations, whose values are each quantized on their own.
  const GaussianSet set = RandomSet(2000, 3, 3);
  const std::vector<uint8_t> bytes = WriteSet(set, FourComponents(GaussianQuantization()));
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 3, &decoded, kMaxGaussiansPerSet, kFour).ok());
  const ParsedSet p = Parse(bytes, 3, kFour);
  ASSERT_EQ(decoded.size(), set.size());
  int k = 0;
  for (int group = 0; group < kNumGaussianGroups; ++group) {
    const int components = GaussianGroupComponents(group, 3);
    const ParsedGroup& g = p.groups[k++];
    for (int r = 0; r < components; ++r) {
      std::vector<float> expected, actual;
      for (size_t i = 0; i < set.size(); ++i) {
        const double x =
            g.Step(r) > 0 ? std::round((double(Component(set, group, i, r)) - g.Min(r)) / g.Step(r))
                          : 0;
        const uint32_t q =
            static_cast<uint32_t>(std::min(std::max(x, 0.0), std::ldexp(1.0, g.bits) - 1));
        expected.push_back(Dequantize(g.Min(r), q, g.Step(r)));
        actual.push_back(Component(decoded, group, i, r));
      }
      std::sort(expected.begin(), expected.end());
      std::sort(actual.begin(), actual.end());
      ASSERT_EQ(expected, actual) << "group " << group << " component " << r;
    }
  }
}

TEST(GaussianSetCodingTest, QuantizeGivesTheDecodedValuesInTheSetsOrder) {
  for (int degree : {0, 1, 3}) {
    for (RotationCoding rotation : {kThree, kFour}) {
      SCOPED_TRACE(degree);
      GaussianSet set = RandomSet(1500, degree, 20 + degree);
      SetIds(&set);
      GaussianQuantization q = WithIds(GaussianQuantization());
      q.syntax = SyntaxOf(rotation);
      q.sh_rest_bits = 3;
      for (size_t i = 0; i < 10; ++i) set.sh[i * set.sh_floats() + 3] = 0.0f;  // a group's zeros
      GaussianSet decoded, quantized = set;
      ASSERT_TRUE(ReconstructGaussianSet(set, q, &decoded).ok());
      ASSERT_TRUE(QuantizeGaussianSet(q, &quantized).ok());
      ASSERT_EQ(quantized.size(), set.size());
      EXPECT_NE(quantized.positions, set.positions);
      for (size_t j = 0; j < decoded.size(); ++j) {
        const size_t i = static_cast<size_t>(std::lround(decoded.opacity_logits[j]));  // its id
        ASSERT_LT(i, set.size());
        for (int group = 0; group < kNumGaussianGroups; ++group) {
          for (int r = 0; r < GaussianGroupComponents(group, degree); ++r) {
            ASSERT_TRUE(
                SameBits(Component(quantized, group, i, r), Component(decoded, group, j, r)))
                << "group " << group << " Gaussian " << i;
          }
        }
      }
      if (degree > 0) {
        for (size_t i = 0; i < 10; ++i) EXPECT_EQ(quantized.sh[i * set.sh_floats() + 3], 0.0f);
      }
    }
  }
  GaussianSet bad = RandomSet(10, 1, 1);
  bad.positions.pop_back();
  EXPECT_EQ(QuantizeGaussianSet(GaussianQuantization(), &bad).code(), M4D_ERR_INVALID_ARG);
}

TEST(GaussianSetCodingTest, EmptySetIsOneByte) {
  GaussianSet set;
  set.sh_degree = 2;
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  EXPECT_EQ(bytes, std::vector<uint8_t>{0});
  GaussianSet decoded = RandomSet(5, 1, 1);
  ASSERT_TRUE(Read(bytes, 2, &decoded).ok());
  EXPECT_EQ(decoded.size(), 0u);
  EXPECT_EQ(decoded.sh_degree, 2);
  EXPECT_TRUE(decoded.sh.empty());
}

TEST(GaussianSetCodingTest, SingleGaussian) {
  for (int degree = 0; degree <= 3; ++degree) {
    GaussianSet set = RandomSet(1, degree, 5);
    SetIds(&set);
    RoundTrip(set, WithIds(GaussianQuantization()));
  }
}

TEST(GaussianSetCodingTest, ConstantGroupsCostNothing) {
  GaussianSet set = RandomSet(300, 2, 11);
  SetIds(&set);
  for (size_t i = 0; i < set.size(); ++i) {
    const float identity[4] = {1, 0, 0, 0};
    std::memcpy(&set.rotations[4 * i], identity, sizeof(identity));
    for (int r = 0; r < 24; ++r) Component(set, kGroupShRest, i, r) = -0.0f;
    set.log_scales[3 * i + 1] = -3;  // one constant component of a varying group
  }
  const std::vector<uint8_t> bytes = WriteSet(set, WithIds(GaussianQuantization()));
  const ParsedSet p = Parse(bytes, 2);
  EXPECT_EQ(p.groups[kGroupRotation].bits, 0);
  EXPECT_EQ(p.groups[kGroupShRest].bits, 0);
  EXPECT_GT(p.groups[kGroupLogScale].bits, 0);
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 2, &decoded).ok());
  ExpectRoundTrip(set, bytes, decoded);
  // -0 + 0 * 0 is +0: the formula applies to constant groups too.
  EXPECT_TRUE(SameBits(Component(decoded, kGroupShRest, 0, 0), 0.0f));
  EXPECT_EQ(decoded.rotations[0], 1.0f);
}

TEST(GaussianSetCodingTest, AllGroupsConstant) {
  GaussianSet set = RandomSet(7, 1, 2);
  for (size_t i = 1; i < set.size(); ++i) {
    for (int group = 0; group < kNumGaussianGroups; ++group) {
      for (int r = 0; r < GaussianGroupComponents(group, 1); ++r) {
        Component(set, group, i, r) = Component(set, group, 0, r);
      }
    }
  }
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  GaussianSet decoded;
  const Status status = Read(bytes, 1, &decoded);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(decoded.positions, set.positions);
  EXPECT_EQ(decoded.sh, set.sh);
}

TEST(GaussianSetCodingTest, LargeSetRoundTrips) {
  GaussianSet set = RandomSet(100000, 3, 99);
  SetIds(&set);
  RoundTrip(set, WithIds(GaussianQuantization()));
}

TEST(GaussianSetCodingTest, WritingIsDeterministic) {
  const GaussianSet set = RandomSet(1000, 1, 4);
  EXPECT_EQ(WriteSet(set, GaussianQuantization()), WriteSet(set, GaussianQuantization()));
}

TEST(GaussianSetCodingTest, WriterRejectsBadInput) {
  GaussianSet set = RandomSet(10, 1, 4);
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  GaussianQuantization q;
  q.sh_rest_bits = 25;
  EXPECT_EQ(WriteGaussianSet(set, q, &w).code(), M4D_ERR_INVALID_ARG);
  set.log_scales[4] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(WriteGaussianSet(set, GaussianQuantization(), &w).code(), M4D_ERR_INVALID_ARG);
  set.log_scales[4] = -1;
  set.sh.pop_back();
  EXPECT_EQ(WriteGaussianSet(set, GaussianQuantization(), &w).code(), M4D_ERR_INVALID_ARG);
}

// Decodes a Draco payload with Draco itself.
std::unique_ptr<draco::PointCloud> DracoDecode(const std::vector<uint8_t>& payload) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(payload.data()), payload.size());
  draco::Decoder decoder;
  auto result = decoder.DecodePointCloudFromBuffer(&buffer);
  EXPECT_TRUE(result.ok());
  return result.ok() ? std::move(result).value() : nullptr;
}

std::vector<uint8_t> DracoEncode(const draco::PointCloud& pc, int method, int prediction) {
  draco::ExpertEncoder encoder(pc);
  encoder.SetSpeedOptions(5, 5);
  encoder.SetEncodingMethod(method);
  if (method == draco::POINT_CLOUD_SEQUENTIAL_ENCODING) {
    for (int j = 0; j < pc.num_attributes(); ++j) {
      EXPECT_TRUE(encoder.SetAttributePredictionScheme(j, prediction).ok());
    }
  }
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(encoder.EncodeToBuffer(&buffer).ok());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

TEST(GaussianSetCodingTest, RejectsKdTreePayloads) {
  // Spec 5.5 allows Draco's sequential method only; a valid kd-tree stream of the same
  // points is refused before Draco decodes it.
  GaussianSet set = RandomSet(2000, 1, 21);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const ParsedSet p = Parse(bytes, 1);
  const std::vector<uint8_t> kd_tree = DracoEncode(
      *DracoDecode(p.draco), draco::POINT_CLOUD_KD_TREE_ENCODING, draco::PREDICTION_NONE);
  ASSERT_EQ(kd_tree[8], draco::POINT_CLOUD_KD_TREE_ENCODING);
  ASSERT_NE(DracoDecode(kd_tree), nullptr);
  GaussianSet decoded;
  const Status status = Read(Reassemble(bytes, p, p.count, kd_tree), 1, &decoded);
  EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
  EXPECT_NE(status.message().find("sequential"), std::string::npos) << status.message();
}

TEST(GaussianSetCodingTest, RejectsEveryTruncation) {
  GaussianSet set = RandomSet(40, 1, 8);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  for (size_t size = 0; size < bytes.size(); ++size) {
    const std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + size);
    GaussianSet decoded;
    EXPECT_EQ(Read(prefix, 1, &decoded).code(), M4D_ERR_BITSTREAM) << size;
  }
  // A shorter Draco payload with a matching draco_size. Draco's tagged symbol scheme stores
  // the raw low bits of its values without a length and reads zeros past the end, so a cut
  // inside the last attribute's bits (the higher SH here) can decode; in a stream the payload
  // CRC refuses it (spec 3). What must hold: a refusal, or every other group decoded intact.
  const ParsedSet p = Parse(bytes, 1);
  GaussianSet full;
  ASSERT_TRUE(Read(bytes, 1, &full).ok());
  size_t refused = 0;
  for (size_t size = 1; size < p.draco.size(); ++size) {
    const std::vector<uint8_t> draco(p.draco.begin(), p.draco.begin() + size);
    GaussianSet decoded;
    const Status status = Read(Reassemble(bytes, p, p.count, draco), 1, &decoded);
    if (!status.ok()) {
      EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM) << size;
      ++refused;
      continue;
    }
    EXPECT_EQ(decoded.positions, full.positions) << size;
    EXPECT_EQ(decoded.log_scales, full.log_scales) << size;
    EXPECT_EQ(decoded.rotations, full.rotations) << size;
    EXPECT_EQ(decoded.opacity_logits, full.opacity_logits) << size;
  }
  // The SH group's raw bits: at most 6 per value (its 5 bits as Draco's signed symbol) of
  // its 9 x 40 values.
  EXPECT_GE(refused, p.draco.size() - 1 - 9 * 40 * 6 / 8) << p.draco.size();
}

TEST(GaussianSetCodingTest, RejectsBadQuantizationParameters) {
  GaussianSet set = RandomSet(30, 1, 9);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const ParsedSet p = Parse(bytes, 1);
  auto expect_error = [&](size_t offset, const void* patch, size_t size) {
    std::vector<uint8_t> bad = bytes;
    std::memcpy(&bad[offset], patch, size);
    GaussianSet decoded;
    EXPECT_EQ(Read(bad, 1, &decoded).code(), M4D_ERR_BITSTREAM) << offset;
  };
  for (const ParsedGroup& g : p.groups) {
    for (uint8_t bits : {25, 32, 255}) expect_error(g.offset, &bits, 1);
    for (uint8_t flag : {2, 255}) expect_error(g.offset + 1, &flag, 1);
    for (float v : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity()}) {
      expect_error(g.offset + 2, &v, 4);  // min
      expect_error(g.offset + 6, &v, 4);  // step
    }
    const float negative = -1.0f;
    expect_error(g.offset + 6, &negative, 4);
  }
}

TEST(GaussianSetCodingTest, RejectsCountsAboveTheLimitBeforeAllocating) {
  const GaussianSet set = RandomSet(50, 0, 10);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  GaussianSet decoded;
  EXPECT_EQ(Read(bytes, 0, &decoded, 49).code(), M4D_ERR_LIMIT);
  EXPECT_TRUE(Read(bytes, 0, &decoded, 50).ok());
  for (uint32_t count : {kMaxGaussiansPerSet + 1, 0xffffffffu}) {
    std::vector<uint8_t> huge;
    ByteWriter w(&huge);
    w.WriteVarUint(count);
    w.WriteBytes(bytes.data() + 1, bytes.size() - 1);
    GaussianSet empty;
    EXPECT_EQ(Read(huge, 0, &empty, 0xffffffffu).code(), M4D_ERR_LIMIT);
    EXPECT_TRUE(empty.positions.empty());
  }
}

TEST(GaussianSetCodingTest, RejectsBadDracoSize) {
  const GaussianSet set = RandomSet(20, 0, 12);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const ParsedSet p = Parse(bytes, 0);
  GaussianSet decoded;
  EXPECT_EQ(Read(Reassemble(bytes, p, p.count, {}), 0, &decoded).code(), M4D_ERR_BITSTREAM);
  std::vector<uint8_t> longer(bytes.begin(), bytes.begin() + p.draco_size_offset);
  ByteWriter w(&longer);
  w.WriteVarUint(static_cast<uint32_t>(p.draco.size() + 1));  // one byte more than remains
  w.WriteBytes(p.draco);
  EXPECT_EQ(Read(longer, 0, &decoded).code(), M4D_ERR_BITSTREAM);
  // A trailing byte inside the Draco payload.
  std::vector<uint8_t> draco = p.draco;
  draco.push_back(0);
  EXPECT_EQ(Read(Reassemble(bytes, p, p.count, draco), 0, &decoded).code(), M4D_ERR_BITSTREAM);
}

TEST(GaussianSetCodingTest, RejectsMismatchingPointCounts) {
  const GaussianSet set = RandomSet(64, 1, 13);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const ParsedSet p = Parse(bytes, 1);
  const std::vector<uint8_t> kd_tree = DracoEncode(
      *DracoDecode(p.draco), draco::POINT_CLOUD_KD_TREE_ENCODING, draco::PREDICTION_NONE);
  for (const std::vector<uint8_t>& draco : {p.draco, kd_tree}) {
    for (uint32_t count : {63u, 65u, 1000u}) {
      GaussianSet decoded;
      EXPECT_EQ(Read(Reassemble(bytes, p, count, draco), 1, &decoded).code(), M4D_ERR_BITSTREAM);
      // Draco's own point count agreeing with the set, its data not.
      std::vector<uint8_t> patched = draco;
      std::memcpy(&patched[11], &count, 4);
      EXPECT_EQ(Read(Reassemble(bytes, p, count, patched), 1, &decoded).code(), M4D_ERR_BITSTREAM);
    }
  }
}

// A Draco payload for the set's groups with one attribute changed by `edit`.
template <typename Edit>
std::vector<uint8_t> EditedPayload(const ParsedSet& p, int method, int prediction, Edit edit) {
  std::unique_ptr<draco::PointCloud> pc = DracoDecode(p.draco);
  draco::PointCloud edited;
  edited.set_num_points(pc->num_points());
  for (int j = 0; j < pc->num_attributes(); ++j) {
    const draco::PointAttribute& att = *pc->attribute(j);
    draco::GeometryAttribute ga;
    ga.Init(att.attribute_type(), nullptr, att.num_components(), att.data_type(), false,
            att.byte_stride(), 0);
    edit(j, &ga);
    const int id = edited.AddAttribute(ga, true, pc->num_points());
    draco::PointAttribute* out = edited.attribute(id);
    for (uint32_t i = 0; i < pc->num_points(); ++i) {
      uint32_t v[64] = {};
      att.ConvertValue<uint32_t>(draco::AttributeValueIndex(i), v);
      std::vector<uint8_t> converted(ga.byte_stride());
      for (int r = 0; r < ga.num_components(); ++r) {
        const size_t size = draco::DataTypeLength(ga.data_type());
        if (ga.data_type() == draco::DT_FLOAT32) {
          const float f = static_cast<float>(v[r]);
          std::memcpy(&converted[r * size], &f, size);
        } else {
          std::memcpy(&converted[r * size], &v[r], size);
        }
      }
      out->SetAttributeValue(draco::AttributeValueIndex(i), converted.data());
    }
  }
  draco::ExpertEncoder encoder(edited);
  encoder.SetSpeedOptions(5, 5);
  encoder.SetEncodingMethod(method);
  for (int j = 0; j < edited.num_attributes(); ++j) {
    if (edited.attribute(j)->data_type() == draco::DT_FLOAT32) {
      encoder.SetAttributeQuantization(j, 14);
    } else if (method == draco::POINT_CLOUD_SEQUENTIAL_ENCODING) {
      encoder.SetAttributePredictionScheme(j, prediction);
    }
  }
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(encoder.EncodeToBuffer(&buffer).ok());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

TEST(GaussianSetCodingTest, RejectsAttributesNotMatchingTheGroups) {
  GaussianSet set = RandomSet(80, 1, 14);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const ParsedSet p = Parse(bytes, 1);
  {
    const int method = draco::POINT_CLOUD_SEQUENTIAL_ENCODING;
    auto expect_error = [&](auto edit) {
      const std::vector<uint8_t> draco =
          EditedPayload(p, method, draco::PREDICTION_DIFFERENCE, edit);
      GaussianSet decoded;
      EXPECT_EQ(Read(Reassemble(bytes, p, p.count, draco), 1, &decoded).code(), M4D_ERR_BITSTREAM);
    };
    // The unchanged payload re-encoded decodes.
    GaussianSet decoded;
    EXPECT_TRUE(Read(Reassemble(bytes, p, p.count,
                                EditedPayload(p, method, draco::PREDICTION_DIFFERENCE,
                                              [](int, draco::GeometryAttribute*) {})),
                     1, &decoded)
                    .ok());
    auto retype = [](int attribute, draco::DataType type) {
      return [=](int j, draco::GeometryAttribute* ga) {
        if (j != attribute) return;
        ga->Init(ga->attribute_type(), nullptr, ga->num_components(), type, false,
                 draco::DataTypeLength(type) * ga->num_components(), 0);
      };
    };
    expect_error(retype(0, draco::DT_UINT32));   // positions are 16-bit: uint16
    expect_error(retype(1, draco::DT_INT8));     // signed
    expect_error(retype(2, draco::DT_FLOAT32));  // Draco's own float quantization
    expect_error([](int j, draco::GeometryAttribute* ga) {
      if (j == 3) {
        ga->Init(draco::GeometryAttribute::COLOR, nullptr, ga->num_components(), ga->data_type(),
                 false, ga->byte_stride(), 0);
      }
    });
  }
}

TEST(GaussianSetCodingTest, RejectsValuesNotBelowTwoToTheBits) {
  GaussianSet set = RandomSet(80, 0, 15);
  GaussianQuantization q;
  q.opacity_bits = 7;  // an 8-bit Draco type holding 7-bit values
  const std::vector<uint8_t> bytes = WriteSet(set, q);
  const ParsedSet p = Parse(bytes, 0);
  std::unique_ptr<draco::PointCloud> pc = DracoDecode(p.draco);
  uint8_t big = 200;
  pc->attribute(kGroupOpacity)->SetAttributeValue(draco::AttributeValueIndex(5), &big);
  {
    const int method = draco::POINT_CLOUD_SEQUENTIAL_ENCODING;
    for (int prediction : {draco::PREDICTION_NONE, draco::PREDICTION_DIFFERENCE}) {
      GaussianSet decoded;
      const Status status =
          Read(Reassemble(bytes, p, p.count, DracoEncode(*pc, method, prediction)), 0, &decoded);
      EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
    }
  }
}

TEST(GaussianSetCodingTest, RejectsGarbageDracoPayloads) {
  const GaussianSet set = RandomSet(100, 1, 16);
  const std::vector<uint8_t> bytes = WriteSet(set, PositionsInDraco());
  const ParsedSet p = Parse(bytes, 1, kThree, false);
  const std::vector<uint8_t> kd_tree = DracoEncode(
      *DracoDecode(p.draco), draco::POINT_CLOUD_KD_TREE_ENCODING, draco::PREDICTION_NONE);
  std::mt19937 rng(17);
  for (const std::vector<uint8_t>& original : {p.draco, kd_tree}) {
    for (int trial = 0; trial < 2000; ++trial) {
      // Pure garbage, or a valid prefix (header, descriptors...) then garbage.
      const size_t keep = trial % 2 ? rng() % original.size() : 0;
      std::vector<uint8_t> draco(original.begin(), original.begin() + keep);
      const size_t extra = 1 + rng() % 400;
      for (size_t i = 0; i < extra; ++i) draco.push_back(static_cast<uint8_t>(rng()));
      GaussianSet decoded;
      EXPECT_FALSE(ReadPositionsInDraco(Reassemble(bytes, p, p.count, draco), 1, &decoded).ok());
    }
  }
}

TEST(GaussianSetCodingTest, RejectsHugeSymbolTablesBeforeDraco) {
  // Draco allocates a declared table (4 bytes an entry, up to 64 entries per payload byte)
  // before reading it; the reader bounds tables to what Draco's encoder writes.
  GaussianSet set = RandomSet(3000, 0, 19);
  bool seen[2] = {false, false};
  for (int position_bits : {24, 0}) {  // first attribute: 24-bit positions, or log scales
    GaussianQuantization q = PositionsInDraco();
    q.position_bits = position_bits;
    const std::vector<uint8_t> bytes = WriteSet(set, q);
    const ParsedSet p = Parse(bytes, 0, kThree, false);
    // The rotation's index is an attribute of its own, without a group header.
    const size_t coded = p.groups.size() + 1 - (position_bits == 0 ? 1 : 0);
    size_t at = 17 + 6 * coded;      // the first attribute's data
    at += p.draco[at] == 0 ? 2 : 1;  // prediction (and its transform)
    at += 1;                         // compressed
    const bool raw = p.draco[at++] == draco::SYMBOL_CODING_RAW;
    seen[raw] = true;
    if (raw) ++at;  // bit length
    size_t end = at;
    while (p.draco[end] & 0x80) ++end;
    std::vector<uint8_t> draco(p.draco.begin(), p.draco.begin() + at);
    ByteWriter w(&draco);
    w.WriteVarUint(1u << 26);
    draco.insert(draco.end(), p.draco.begin() + end + 1, p.draco.end());
    GaussianSet decoded;
    const Status status = ReadPositionsInDraco(Reassemble(bytes, p, p.count, draco), 0, &decoded);
    EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
    EXPECT_NE(status.message().find("too large"), std::string::npos) << status.message();
  }
  EXPECT_TRUE(seen[0] && seen[1]) << "both symbol schemes";
}

TEST(GaussianSetCodingTest, SurvivesFlippedBytesInTheDracoPayload) {
  GaussianSet set = RandomSet(60, 1, 18);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const ParsedSet p = Parse(bytes, 1);
  const std::vector<uint8_t> kd_tree = DracoEncode(
      *DracoDecode(p.draco), draco::POINT_CLOUD_KD_TREE_ENCODING, draco::PREDICTION_NONE);
  for (const std::vector<uint8_t>& original : {p.draco, kd_tree}) {
    int errors = 0, trials = 0;
    for (size_t i = 0; i < original.size(); ++i) {
      for (uint8_t mask : {static_cast<uint8_t>(1u << (i % 8)), static_cast<uint8_t>(0xff)}) {
        std::vector<uint8_t> draco = original;
        draco[i] ^= mask;
        GaussianSet decoded;
        const Status status = Read(Reassemble(bytes, p, p.count, draco), 1, &decoded);
        ++trials;
        if (status.ok()) {
          EXPECT_EQ(decoded.size(), set.size());
        } else {
          EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM) << status.message();
          ++errors;
        }
      }
    }
    EXPECT_GT(errors, 0) << trials << " trials";
  }
}

TEST(GaussianSetCodingTest, SmallestThreeKeepsTheRotationInFewerBytes) {
  GaussianSet set = RandomSet(5000, 1, 41);
  SetIds(&set);
  GaussianQuantization q = WithIds(GaussianQuantization());
  const std::vector<uint8_t> three = WriteSet(set, q);
  const std::vector<uint8_t> four = WriteSet(set, FourComponents(q));
  EXPECT_LT(three.size() + 5000 / 8, four.size());  // at least a bit per Gaussian
  GaussianSet decoded;
  ASSERT_TRUE(Read(three, 1, &decoded).ok());
  // Each decoded quaternion is the unit one (up to its sign) within the step of 10 bits.
  for (size_t j = 0; j < decoded.size(); ++j) {
    const size_t i = static_cast<size_t>(std::lround(decoded.opacity_logits[j]));
    const float* o = &set.rotations[4 * i];
    const float* d = &decoded.rotations[4 * j];
    const double norm = std::sqrt(double(o[0]) * o[0] + double(o[1]) * o[1] + double(o[2]) * o[2] +
                                  double(o[3]) * o[3]);
    double dot = 0;
    for (int r = 0; r < 4; ++r) dot += d[r] * o[r] / norm;
    ASSERT_GT(std::fabs(dot), 1.0 - 1e-4) << i;
  }
}

// Mean relative Frobenius error of the decoded covariances against the originals'.
double CovarianceError(const GaussianSet& original, const GaussianSet& decoded) {
  double sum = 0.0;
  for (size_t j = 0; j < decoded.size(); ++j) {
    const size_t i = static_cast<size_t>(std::lround(decoded.opacity_logits[j]));
    sum += testing::RelativeDifference(testing::Covariance(decoded, j),
                                       testing::Covariance(original, i));
  }
  return sum / static_cast<double>(decoded.size());
}

TEST(GaussianSetCodingTest, CanonicalRotationsTakeOneBitLessForTheSameShapes) {
  GaussianSet set = RandomSet(5000, 1, 43);
  for (float& v : set.log_scales) v = v / 4 - 2;  // no axis far below the scales' step
  SetIds(&set);
  GaussianQuantization canonical = WithIds(GaussianQuantization());
  canonical.canonical_rotations = true;
  canonical.log_scale_bits = 12;
  canonical.rotation_bits = 5;
  GaussianQuantization given = canonical;
  given.canonical_rotations = false;
  given.rotation_bits = 6;
  const std::vector<uint8_t> fewer = WriteSet(set, canonical), more = WriteSet(set, given);
  GaussianSet from_fewer, from_more;
  ASSERT_TRUE(Read(fewer, 1, &from_fewer).ok());
  ASSERT_TRUE(Read(more, 1, &from_more).ok());
  const double error_fewer = CovarianceError(set, from_fewer);
  EXPECT_LT(error_fewer, CovarianceError(set, from_more));
  EXPECT_LT(fewer.size() + 5000 * 2 / 8, more.size());  // 3 bits less, at least 2 coded
  // Every decoded rotation is canonical: w the largest component, so the index is always 0.
  const float step = Parse(fewer, 1).groups[kGroupRotation].step[0];
  for (size_t j = 0; j < from_fewer.size(); ++j) {
    for (int c = 1; c < 4; ++c) {
      ASSERT_LE(std::fabs(from_fewer.rotations[4 * j + c]), kCanonicalRotationBound + step) << j;
    }
  }
}

TEST(GaussianSetCodingTest, QuantizeKeepsEachGaussiansAxesWithCanonicalRotations) {
  GaussianSet set = RandomSet(2000, 1, 44);
  SetIds(&set);
  GaussianQuantization q = WithIds(GaussianQuantization());
  q.canonical_rotations = true;
  GaussianSet decoded, quantized = set;
  ASSERT_TRUE(ReconstructGaussianSet(set, q, &decoded).ok());
  ASSERT_TRUE(QuantizeGaussianSet(q, &quantized).ok());
  for (size_t j = 0; j < decoded.size(); ++j) {
    const size_t i = static_cast<size_t>(std::lround(decoded.opacity_logits[j]));
    // The decoder's Gaussian (up to the f32 rounding of turning it back)...
    ASSERT_LT(testing::RelativeDifference(testing::Covariance(quantized, i),
                                          testing::Covariance(decoded, j)),
              1e-5)
        << i;
    // ...in the set's own parameters: its axis order and its quaternion's sign.
    double dot = 0.0;
    for (int c = 0; c < 4; ++c) {
      dot += double{quantized.rotations[4 * i + c]} * set.rotations[4 * i + c];
    }
    EXPECT_GT(dot, 0.0) << i;
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(quantized.log_scales[3 * i + r], set.log_scales[3 * i + r], 0.02) << i;
    }
  }
}

TEST(GaussianSetCodingTest, SmallestThreeOfConstantAndDegenerateRotations) {
  GaussianSet set = RandomSet(200, 0, 42);
  auto expect_rotation = [&](const GaussianSet& decoded, size_t i, std::vector<float> q) {
    EXPECT_EQ(std::vector<float>(&decoded.rotations[4 * i], &decoded.rotations[4 * i + 4]), q) << i;
  };
  // One rotation for all, not the identity: coded with index 0, as a constant group.
  for (size_t i = 0; i < set.size(); ++i) {
    const float turned[4] = {0, -2, 0, 0};
    std::memcpy(&set.rotations[4 * i], turned, sizeof(turned));
  }
  std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  EXPECT_EQ(Parse(bytes, 0).groups[kGroupRotation].bits, 0);
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 0, &decoded).ok());
  for (size_t i = 0; i < set.size(); ++i) expect_rotation(decoded, i, {0, -1, 0, 0});
  // Two rotations whose three smallest components are equal: the index must travel.
  SetIds(&set);
  for (size_t i = 0; i < set.size(); i += 2) {
    const float identity[4] = {1, 0, 0, 0};
    std::memcpy(&set.rotations[4 * i], identity, sizeof(identity));
  }
  bytes = WriteSet(set, WithIds(GaussianQuantization()));
  EXPECT_GT(Parse(bytes, 0).groups[kGroupRotation].bits, 0);
  ASSERT_TRUE(Read(bytes, 0, &decoded).ok());
  for (size_t j = 0; j < set.size(); ++j) {
    const size_t i = static_cast<size_t>(std::lround(decoded.opacity_logits[j]));
    expect_rotation(decoded, j,
                    i % 2 == 0 ? std::vector<float>{1, 0, 0, 0} : std::vector<float>{0, 1, 0, 0});
  }
  std::fill(set.rotations.begin(), set.rotations.end(), 0.0f);  // no rotation: the identity
  bytes = WriteSet(set, GaussianQuantization());
  EXPECT_EQ(Parse(bytes, 0).groups[kGroupRotation].bits, 0);
  ASSERT_TRUE(Read(bytes, 0, &decoded).ok());
  expect_rotation(decoded, 0, {1, 0, 0, 0});
}

TEST(GaussianSetCodingTest, ComposeSmallestThreeRoundsEachOperation) {
  const float abc[3] = {0.6f, -0.1f, 0.3f};
  float q[4];
  ComposeSmallestThree(abc, 2, q);
  float sum = abc[0] * abc[0];
  sum += abc[1] * abc[1];
  sum += abc[2] * abc[2];
  EXPECT_TRUE(SameBits(q[2], std::sqrt(1.0f - sum)));
  EXPECT_EQ(q[0], 0.6f);
  EXPECT_EQ(q[1], -0.1f);
  EXPECT_EQ(q[3], 0.3f);
  const float too_long[3] = {0.75f, 0.75f, 0.0f};  // 1 - (a^2 + b^2 + c^2) < 0: clamped
  ComposeSmallestThree(too_long, 0, q);
  EXPECT_EQ(q[0], 0.0f);
  ComposeSmallestThree(abc, 0, q);
  // In place: abc aliasing q[0..2].
  float in_place[4] = {0.6f, -0.1f, 0.3f, 9.0f};
  ComposeSmallestThree(in_place, 0, in_place);
  for (int r = 0; r < 4; ++r) EXPECT_TRUE(SameBits(in_place[r], q[r]));
}

TEST(GaussianSetCodingTest, RejectsARotationIndexAboveThree) {
  GaussianSet set = RandomSet(100, 0, 43);
  const std::vector<uint8_t> bytes = WriteSet(set, PositionsInDraco());
  const ParsedSet p = Parse(bytes, 0, kThree, false);
  std::unique_ptr<draco::PointCloud> pc = DracoDecode(p.draco);
  ASSERT_EQ(pc->num_attributes(), 6);  // position, scale, rotation, its index, opacity, DC
  draco::PointAttribute* index = pc->attribute(3);
  ASSERT_EQ(index->num_components(), 1);
  for (uint8_t bad : {4, 255}) {
    index->SetAttributeValue(draco::AttributeValueIndex(7), &bad);
    const std::vector<uint8_t> draco =
        DracoEncode(*pc, draco::POINT_CLOUD_SEQUENTIAL_ENCODING, draco::PREDICTION_NONE);
    GaussianSet decoded;
    const Status status = ReadPositionsInDraco(Reassemble(bytes, p, p.count, draco), 0, &decoded);
    EXPECT_EQ(status.code(), M4D_ERR_BITSTREAM);
    EXPECT_NE(status.message().find("rotation index"), std::string::npos) << status.message();
  }
  // The same payload with the index in range decodes: the refusal is the index's.
  const uint8_t good = 3;
  index->SetAttributeValue(draco::AttributeValueIndex(7), &good);
  GaussianSet decoded;
  EXPECT_TRUE(
      ReadPositionsInDraco(Reassemble(bytes, p, p.count,
                                      DracoEncode(*pc, draco::POINT_CLOUD_SEQUENTIAL_ENCODING,
                                                  draco::PREDICTION_NONE)),
                           0, &decoded)
          .ok());
}

}  // namespace
}  // namespace m4d

namespace m4d {
namespace {

// Version 0.7 (spec 5.6): the writer codes positions as an octree where that is smaller than
// Draco's attribute, on keyframe-like sets, and keeps Draco's on small ones; both decode to the
// positions 0.6's syntax gives.
TEST(GaussianSetCodingTest, PositionsAreAnOctreeWhereThatIsSmaller) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (size_t n : {size_t{40}, size_t{20000}}) {
    GaussianSet set = RandomSet(n, 1, 7);
    for (size_t i = 0; i < n; ++i) {  // a wavy surface, as trained Gaussians lie on
      const float x = u(rng), y = u(rng);
      set.positions[3 * i] = x;
      set.positions[3 * i + 1] = y;
      set.positions[3 * i + 2] = 0.2f * std::sin(3.0f * x) * std::cos(2.0f * y);
    }
    const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
    const std::vector<uint8_t> v06 = WriteSet(set, PositionsInDraco());
    const ParsedSet p = Parse(bytes, 1);
    EXPECT_EQ(p.octree, n > 40) << n;
    if (p.octree) {
      EXPECT_LT(bytes.size(), v06.size()) << n;
    }
    EXPECT_LE(bytes.size(), v06.size() + 1) << n;  // the flag at most
    GaussianSet decoded, decoded_v06;
    ASSERT_TRUE(Read(bytes, 1, &decoded).ok());
    ASSERT_TRUE(ReadPositionsInDraco(v06, 1, &decoded_v06).ok());
    EXPECT_EQ(decoded.positions, decoded_v06.positions) << n;
    EXPECT_EQ(decoded.sh, decoded_v06.sh) << n;
  }
  // A flag other than 0 or 1.
  const std::vector<uint8_t> bytes = WriteSet(RandomSet(40, 1, 8), GaussianQuantization());
  const ParsedSet p = Parse(bytes, 1);
  std::vector<uint8_t> bad = bytes;
  bad[p.draco_size_offset - 1] = 2;
  GaussianSet decoded;
  EXPECT_EQ(Read(bad, 1, &decoded).code(), M4D_ERR_BITSTREAM);
}

}  // namespace
}  // namespace m4d
