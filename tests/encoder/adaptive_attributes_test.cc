// Adaptive attributes (bitstream-spec 5.4, 5.7, version 0.8): the binary range coder round
// trips, a set coded with adaptive attributes decodes to exactly the values Draco's coding of
// the same set gives, the writer takes whichever is smaller, and the reader refuses every
// malformed payload.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "encoder/src/entropy/binary_range_encoder.h"
#include "encoder/src/layers/adaptive_attributes_writer.h"
#include "encoder/src/layers/gaussian_set_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/entropy/binary_range_decoder.h"
#include "sdk/src/layers/adaptive_attributes.h"
#include "sdk/src/layers/gaussian_set_reader.h"
#include "tests/encoder/gaussian_set_test_util.h"

namespace m4d {
namespace {

using testing::WriteSet;

constexpr BitProbability kHalf = 1u << (kRangeProbabilityBits - 1);

// Bits drawn with a probability of 1 that changes along the sequence, each coded with one of
// four adaptive probabilities or as a bypass bit.
struct BitSequence {
  std::vector<int> bits, kinds;  // kind 0..3: that probability; 4: bypass
};

BitSequence RandomBits(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  BitSequence s;
  for (size_t i = 0; i < n; ++i) {
    const int kind = static_cast<int>(rng() % 5);
    const double p1 = kind == 4 ? 0.5 : 0.02 + 0.3 * kind * (i < n / 2 ? 1.0 : 0.2);
    s.kinds.push_back(kind);
    s.bits.push_back(std::uniform_real_distribution<double>(0, 1)(rng) < p1 ? 1 : 0);
  }
  return s;
}

std::vector<uint8_t> EncodeBits(const BitSequence& s) {
  BinaryRangeEncoder encoder;
  BitProbability p[4] = {kHalf, kHalf, kHalf, kHalf};
  for (size_t i = 0; i < s.bits.size(); ++i) {
    if (s.kinds[i] == 4) {
      encoder.EncodeBypassBit(s.bits[i]);
    } else {
      encoder.EncodeBit(&p[s.kinds[i]], s.bits[i]);
    }
  }
  return encoder.Finish();
}

// Decodes s.bits.size() bits of the kinds in `s`; true when they equal s.bits.
bool DecodesTo(const std::vector<uint8_t>& payload, const BitSequence& s,
               BinaryRangeDecoder* decoder) {
  BitProbability p[4] = {kHalf, kHalf, kHalf, kHalf};
  bool equal = true;
  for (size_t i = 0; i < s.bits.size(); ++i) {
    const int bit =
        s.kinds[i] == 4 ? decoder->DecodeBypassBit() : decoder->DecodeBit(&p[s.kinds[i]]);
    equal = equal && bit == s.bits[i];
  }
  return equal;
}

TEST(BinaryRangeCoder, RoundTripsAndReadsThePayloadExactly) {
  for (size_t n : {0, 1, 7, 100, 5000, 200000}) {
    SCOPED_TRACE(n);
    const BitSequence s = RandomBits(n, static_cast<uint32_t>(n) + 1);
    const std::vector<uint8_t> payload = EncodeBits(s);
    ASSERT_GE(payload.size(), 4u);
    BinaryRangeDecoder decoder(payload.data(), payload.size());
    EXPECT_TRUE(DecodesTo(payload, s, &decoder));
    EXPECT_TRUE(decoder.consumed_exactly());
  }
}

TEST(BinaryRangeCoder, SkewedBitsCostLessThanABit) {
  BitSequence s;
  for (int i = 0; i < 100000; ++i) {
    s.bits.push_back(i % 50 == 0 ? 1 : 0);
    s.kinds.push_back(0);
  }
  // Entropy of p = 0.02: 0.141 bits; the adaptive probability's own noise costs a little more.
  EXPECT_LT(EncodeBits(s).size(), 100000 * 0.17 / 8);
}

TEST(BinaryRangeCoder, ShortAndLongPayloadsAreDetected) {
  const BitSequence s = RandomBits(20000, 3);
  std::vector<uint8_t> payload = EncodeBits(s);
  std::vector<uint8_t> shorter(payload.begin(), payload.end() - 1);
  BinaryRangeDecoder short_decoder(shorter.data(), shorter.size());
  DecodesTo(shorter, s, &short_decoder);
  EXPECT_TRUE(short_decoder.overran());
  EXPECT_FALSE(short_decoder.consumed_exactly());
  payload.push_back(0);
  BinaryRangeDecoder long_decoder(payload.data(), payload.size());
  EXPECT_TRUE(DecodesTo(payload, s, &long_decoder));
  EXPECT_FALSE(long_decoder.overran());
  EXPECT_FALSE(long_decoder.consumed_exactly());
}

// Attributes whose distribution changes from region to region, as a trained keyframe's do (a
// surface's colours and sizes): in each of 125 cells of space every value is uniform over its
// own quarter of the range. Neighbours in Morton order then say where a value lies, not what
// it is: where adaptive attributes beat Draco's differences.
GaussianSet RegionalSet(size_t n, int sh_degree, uint32_t seed) {
  testing::UniformFloats uniform(seed);
  GaussianSet set = testing::ZeroSet(n, sh_degree);
  const size_t k = static_cast<size_t>(set.sh_floats());
  const size_t values = 3 + 4 + 1 + k;
  std::vector<float> quarter(125 * values);
  for (float& v : quarter) v = uniform(0, 0.75f);
  for (size_t i = 0; i < n; ++i) {
    float* p = &set.positions[3 * i];
    for (int r = 0; r < 3; ++r) p[r] = uniform(-10, 10);
    const int cell = static_cast<int>((p[0] + 10) / 4) + 5 * static_cast<int>((p[1] + 10) / 4) +
                     25 * static_cast<int>((p[2] + 10) / 4);
    const float* o = &quarter[static_cast<size_t>(std::min(cell, 124)) * values];
    auto value = [&](size_t j, float lo, float hi) {
      return lo + (hi - lo) * (o[j] + uniform(0, 0.25f));
    };
    for (size_t r = 0; r < 3; ++r) set.log_scales[3 * i + r] = value(r, -7, -1);
    for (size_t r = 0; r < 4; ++r) set.rotations[4 * i + r] = value(3 + r, -1, 1);
    set.opacity_logits[i] = value(7, -5, 5);
    for (size_t r = 0; r < k; ++r) set.sh[i * k + r] = value(8 + r, -2, 2);
  }
  return set;
}

Status Read(const std::vector<uint8_t>& bytes, int sh_degree, GaussianSet* out,
            const GaussianSetSyntax& syntax = GaussianSetSyntax()) {
  ByteReader r(bytes.data(), bytes.size());
  const Status status = ReadGaussianSet(&r, sh_degree, syntax, kMaxGaussiansPerSet, out);
  if (status.ok() && r.remaining() != 0) return BitstreamError("bytes left after the set");
  return status;
}

GaussianQuantization Coded(GaussianQuantization q, AttributeCoding coding) {
  q.attribute_coding = coding;
  return q;
}

// Decodes the set coded both ways; their decoded values must be equal.
void ExpectSameDecode(const GaussianSet& set, const GaussianQuantization& q) {
  GaussianSet adaptive, draco;
  const Status a =
      Read(WriteSet(set, Coded(q, AttributeCoding::kAdaptive)), set.sh_degree, &adaptive);
  const Status d = Read(WriteSet(set, Coded(q, AttributeCoding::kDraco)), set.sh_degree, &draco);
  ASSERT_TRUE(a.ok()) << a.message();
  ASSERT_TRUE(d.ok()) << d.message();
  EXPECT_EQ(adaptive.positions, draco.positions);
  EXPECT_EQ(adaptive.log_scales, draco.log_scales);
  EXPECT_EQ(adaptive.rotations, draco.rotations);
  EXPECT_EQ(adaptive.opacity_logits, draco.opacity_logits);
  EXPECT_EQ(adaptive.sh, draco.sh);
}

TEST(AdaptiveAttributes, DecodeAsDracoDoesAtEveryShDegree) {
  for (int degree = 0; degree <= 3; ++degree) {
    SCOPED_TRACE(degree);
    ExpectSameDecode(RegionalSet(3000, degree, 10 + degree), GaussianQuantization());
  }
}

// Widths above kAdaptiveTreeBits code their low bits as bypass bits; 1 and 2 bits have fewer
// context bits than kAdaptiveContextBits.
TEST(AdaptiveAttributes, DecodeAsDracoDoesAtEveryWidth) {
  const GaussianSet set = RegionalSet(1500, 1, 5);
  for (int bits : {1, 2, 3, 8, 9, 13, 24}) {
    SCOPED_TRACE(bits);
    GaussianQuantization q;
    q.log_scale_bits = q.rotation_bits = q.opacity_bits = q.sh_dc_bits = q.sh_rest_bits = bits;
    ExpectSameDecode(set, q);
  }
}

TEST(AdaptiveAttributes, DecodeAsDracoDoesWithCodebooksAndConstantGroups) {
  GaussianSet set = RegionalSet(9000, 1, 6);
  for (size_t i = 0; i < set.size(); ++i) set.opacity_logits[i] = 2.0f;  // bits 0 in effect
  GaussianQuantization q;
  q.sh_dc_codebook = 256;
  q.sh_rest_codebook = 5;  // an index width of 3 with values 5..7 never used
  q.log_scale_codebook = 16;
  q.codebooks_only_where_they_pay = false;
  ExpectSameDecode(set, q);
  q.rotation_bits = 0;  // no rotation index either
  q.position_bits = 0;  // no octree, no Draco payload at all
  ExpectSameDecode(set, q);
}

TEST(AdaptiveAttributes, TheWriterTakesTheSmallerCoding) {
  GaussianQuantization q;  // rate point r1's bits
  q.position_bits = 12;
  q.log_scale_bits = q.opacity_bits = q.sh_dc_bits = 5;
  q.rotation_bits = 6;
  q.sh_rest_bits = 3;
  const GaussianSet smooth = RegionalSet(20000, 1, 8);
  const size_t smaller = WriteSet(smooth, q).size();
  const size_t adaptive = WriteSet(smooth, Coded(q, AttributeCoding::kAdaptive)).size();
  const size_t draco = WriteSet(smooth, Coded(q, AttributeCoding::kDraco)).size();
  EXPECT_LT(adaptive, draco);  // neighbours say where values lie here (2.7 % smaller)
  EXPECT_EQ(smaller, adaptive);
  // A handful of Gaussians: four bytes of range coder against Draco's few bits.
  const GaussianSet tiny = RegionalSet(2, 0, 9);
  GaussianQuantization narrow = q;
  narrow.log_scale_bits = narrow.rotation_bits = narrow.sh_dc_bits = 1;
  narrow.opacity_bits = 0;
  EXPECT_EQ(WriteSet(tiny, narrow).size(),
            std::min(WriteSet(tiny, Coded(narrow, AttributeCoding::kAdaptive)).size(),
                     WriteSet(tiny, Coded(narrow, AttributeCoding::kDraco)).size()));
}

// Colours of one brightness each, unrelated between neighbours: a Gaussian's channels say what
// its other channels are, its neighbour does not. From 0.11 SH DC codes on the previous channel
// (spec 5.7), and both versions decode to the same values.
TEST(AdaptiveAttributes, ShDcChannelsAreCodedOnThePreviousChannelFromVersion0_11) {
  GaussianSet set = RegionalSet(20000, 0, 14);
  testing::UniformFloats uniform(15);
  for (size_t i = 0; i < set.size(); ++i) {
    const float grey = uniform(-1.5f, 1.5f);
    for (size_t r = 0; r < 3; ++r) set.sh[3 * i + r] = grey + uniform(-0.05f, 0.05f);
  }
  GaussianQuantization q = Coded(GaussianQuantization(), AttributeCoding::kAdaptive);
  GaussianQuantization v10 = q;
  v10.syntax.sh_dc_channel_context = false;
  GaussianSetSyntax v10_syntax;
  v10_syntax.sh_dc_channel_context = false;
  const std::vector<uint8_t> channel = WriteSet(set, q), own = WriteSet(set, v10);
  GaussianSet a, b;
  ASSERT_TRUE(Read(channel, 0, &a).ok());
  ASSERT_TRUE(Read(own, 0, &b, v10_syntax).ok());
  EXPECT_EQ(a.sh, b.sh);
  EXPECT_EQ(a.log_scales, b.log_scales);
  // The same values in 2 bits fewer per Gaussian (2.5 measured): the previous channel's top 5
  // bits narrow a later channel to 16 of its 256 levels, the own context's top 3 to 64.
  EXPECT_LT(channel.size() + 2 * set.size() / 8, own.size());
  // Read with the other version's context, the payload decodes to other colours or fails.
  GaussianSet c;
  const Status crossed = Read(channel, 0, &c, v10_syntax);
  EXPECT_TRUE(!crossed.ok() || c.sh != a.sh);
}

// Higher SH of degree 3 at 5 bits: 24 + 30 + 2 + 8 + 24 + 225 decisions per Gaussian, above
// kMaxAdaptiveBinsPerGaussian: Draco's faster decoding is kept, though adaptive is smaller.
TEST(AdaptiveAttributes, SetsOfManyDecisionsPerGaussianKeepDraco) {
  const GaussianSet set = RegionalSet(20000, 3, 13);
  const GaussianQuantization q;
  const size_t adaptive = WriteSet(set, Coded(q, AttributeCoding::kAdaptive)).size();
  const size_t draco = WriteSet(set, Coded(q, AttributeCoding::kDraco)).size();
  EXPECT_LT(adaptive, draco);
  EXPECT_EQ(WriteSet(set, q).size(), draco);
}

// The byte of attribute_coding: where the set coded with Draco under 0.8 differs from 0.7.
size_t AttributeCodingOffset(const GaussianSet& set, GaussianQuantization q) {
  q.attribute_coding = AttributeCoding::kDraco;
  const std::vector<uint8_t> v8 = WriteSet(set, q);
  q.syntax.adaptive_attributes = false;
  const std::vector<uint8_t> v7 = WriteSet(set, q);
  size_t k = 0;
  while (k < v7.size() && v7[k] == v8[k]) ++k;
  EXPECT_EQ(v8.size(), v7.size() + 1);
  EXPECT_EQ(v8[k], 0);
  return k;
}

TEST(AdaptiveAttributes, AttributeCodingOtherThanZeroOrOneIsRefused) {
  const GaussianSet set = RegionalSet(500, 1, 11);
  const size_t k = AttributeCodingOffset(set, GaussianQuantization());
  std::vector<uint8_t> bytes =
      WriteSet(set, Coded(GaussianQuantization(), AttributeCoding::kDraco));
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 1, &decoded).ok());
  for (uint8_t flag : {2, 255}) {
    bytes[k] = flag;
    EXPECT_EQ(Read(bytes, 1, &decoded).code(), M4D_ERR_BITSTREAM);
  }
}

TEST(AdaptiveAttributes, EveryTruncationAndAppendedByteIsRefused) {
  const GaussianSet set = RegionalSet(400, 1, 12);
  const std::vector<uint8_t> bytes =
      WriteSet(set, Coded(GaussianQuantization(), AttributeCoding::kAdaptive));
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 1, &decoded).ok());
  for (size_t n = 0; n < bytes.size(); ++n) {
    const std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + n);
    EXPECT_NE(Read(prefix, 1, &decoded).code(), M4D_OK) << n;
  }
}

// Values coded past their limit: the payload size field and payload of adaptive_attributes().
std::vector<uint8_t> AdaptivePayload(std::vector<uint32_t> values, int width, uint32_t limit) {
  AdaptiveField field;
  field.components = 1;
  field.width = width;
  field.limit = limit;
  field.q = values.data();
  const std::vector<uint8_t> payload =
      EncodeAdaptiveAttributes(&field, 1, static_cast<uint32_t>(values.size()));
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  w.WriteVarUint(static_cast<uint32_t>(payload.size()));
  w.WriteBytes(payload.data(), payload.size());
  return bytes;
}

Status ReadIndices(const std::vector<uint8_t>& bytes, uint32_t count, int width, uint32_t limit) {
  std::vector<uint32_t> q(count);
  AdaptiveField field;
  field.components = 1;
  field.width = width;
  field.limit = limit;
  field.q = q.data();
  ByteReader r(bytes.data(), bytes.size());
  return ReadAdaptiveAttributes(&r, &field, 1, count);
}

TEST(AdaptiveAttributes, AnIndexAtOrAboveTheCodebookSizeIsRefused) {
  const std::vector<uint8_t> valid = AdaptivePayload({0, 4, 3, 1}, 3, 8);
  EXPECT_TRUE(ReadIndices(valid, 4, 3, 5).ok());
  const std::vector<uint8_t> above = AdaptivePayload({0, 4, 5, 1}, 3, 8);
  EXPECT_TRUE(ReadIndices(above, 4, 3, 8).ok());
  EXPECT_EQ(ReadIndices(above, 4, 3, 5).code(), M4D_ERR_BITSTREAM);
}

TEST(AdaptiveAttributes, PayloadsBelowFourBytesOrNotConsumedAreRefused) {
  std::vector<uint8_t> bytes = AdaptivePayload(std::vector<uint32_t>(1000, 3), 4, 16);
  EXPECT_TRUE(ReadIndices(bytes, 1000, 4, 16).ok());
  EXPECT_EQ(ReadIndices({3, 0, 0, 0}, 0, 4, 16).code(), M4D_ERR_BITSTREAM);
  EXPECT_TRUE(ReadIndices({4, 0, 0, 0, 0}, 0, 4, 16).ok());
  EXPECT_EQ(ReadIndices({5, 0, 0, 0, 0, 0}, 0, 4, 16).code(), M4D_ERR_BITSTREAM);
}

}  // namespace
}  // namespace m4d
