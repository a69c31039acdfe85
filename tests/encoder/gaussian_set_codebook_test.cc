// Codebooks in gaussian_set() (bitstream-spec 5.4, 5.5, version 0.6): every decoded value of a
// codebook group is one of its K entries, the writer keeps a codebook only where it pays, and
// the reader refuses codebooks the spec does not allow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <vector>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/gaussian_set_reader.h"
#include "tests/encoder/gaussian_set_test_util.h"

namespace m4d {
namespace {

using testing::WriteSet;

// Colours and scales drawn around `clusters` centres with a little noise, as a trained
// keyframe's cluster; positions and rotations uniform.
GaussianSet ClusteredSet(size_t n, int sh_degree, int clusters, uint32_t seed) {
  testing::UniformFloats uniform(seed);
  GaussianSet set = testing::ZeroSet(n, sh_degree);
  const size_t k = static_cast<size_t>(set.sh_floats());
  std::vector<float> centres(static_cast<size_t>(clusters) * (k + 3));
  for (float& v : centres) v = uniform(-1, 1);
  for (size_t i = 0; i < n; ++i) {
    const float* c = &centres[(uniform.Next() % clusters) * (k + 3)];
    for (size_t r = 0; r < k; ++r) set.sh[i * k + r] = c[r] + uniform(-0.01f, 0.01f);
    for (size_t r = 0; r < 3; ++r)
      set.log_scales[3 * i + r] = c[k + r] - 4 + uniform(-0.01f, 0.01f);
    for (size_t r = 0; r < 3; ++r) set.positions[3 * i + r] = uniform(-10, 10);
    for (size_t r = 0; r < 4; ++r) set.rotations[4 * i + r] = uniform(-1, 1);
    set.opacity_logits[i] = uniform(-5, 5);
  }
  return set;
}

GaussianQuantization Codebooks(int size) {
  GaussianQuantization q;
  q.log_scale_codebook = q.sh_dc_codebook = q.sh_rest_codebook = size;
  return q;
}

Status Read(const std::vector<uint8_t>& bytes, int sh_degree, GaussianSet* out,
            GaussianSetSyntax syntax = GaussianSetSyntax()) {
  ByteReader r(bytes.data(), bytes.size());
  return ReadGaussianSet(&r, sh_degree, syntax, kMaxGaussiansPerSet, out);
}

// The header of a set written with the newest syntax: each group's codebook_size and where it
// is in `bytes`.
struct Header {
  std::vector<uint32_t> codebook_sizes;
  std::vector<size_t> codebook_offsets;
};

Header ParseHeader(const std::vector<uint8_t>& bytes, int sh_degree) {
  Header h;
  ByteReader r(bytes.data(), bytes.size());
  uint32_t count = 0;
  EXPECT_TRUE(r.ReadVarUint(&count));
  for (int group = 0; group < kNumGaussianGroups; ++group) {
    const int c = CodedGroupComponents(group, sh_degree, RotationCoding::kSmallestThree);
    if (c == 0) continue;
    uint8_t bits = 0, per_component = 0;
    EXPECT_TRUE(r.ReadU8(&bits) && r.ReadU8(&per_component));
    const uint8_t* skipped;
    EXPECT_TRUE(r.ReadBytes(8u * (per_component ? c : 1), &skipped));
    h.codebook_offsets.push_back(r.position());
    uint32_t size = 0;
    EXPECT_TRUE(r.ReadVarUint(&size));
    h.codebook_sizes.push_back(size);
    if (size > 0) {
      std::vector<int32_t> entries(size * c);
      EXPECT_TRUE(ReadSymbolBlock(&r, RansLayout::kInterleaved, size * c, 0, (1 << bits) - 1,
                                  entries.data())
                      .ok());
    }
  }
  return h;
}

// The distinct vectors of a group's components in a decoded set.
std::set<std::vector<float>> DistinctVectors(const GaussianSet& set, int group) {
  std::set<std::vector<float>> vectors;
  const size_t k = static_cast<size_t>(set.sh_floats());
  for (size_t i = 0; i < set.size(); ++i) {
    if (group == kGroupLogScale) {
      vectors.insert({&set.log_scales[3 * i], &set.log_scales[3 * i] + 3});
    } else if (group == kGroupShDc) {
      vectors.insert({&set.sh[i * k], &set.sh[i * k] + 3});
    } else {
      vectors.insert({&set.sh[i * k] + 3, &set.sh[i * k] + k});
    }
  }
  return vectors;
}

TEST(GaussianSetCodebookTest, EveryValueIsOneOfTheEntries) {
  for (int size : {16, 300}) {
    SCOPED_TRACE(size);
    const size_t n = static_cast<size_t>(kCodebookMinGaussiansPerEntry) * size;
    const GaussianSet set = ClusteredSet(n, 2, 40, 3);
    GaussianQuantization q = Codebooks(size);
    q.codebooks_only_where_they_pay = false;
    const std::vector<uint8_t> bytes = WriteSet(set, q);
    const Header header = ParseHeader(bytes, 2);
    EXPECT_EQ(header.codebook_sizes,
              (std::vector<uint32_t>{0, static_cast<uint32_t>(size), 0, 0,
                                     static_cast<uint32_t>(size), static_cast<uint32_t>(size)}));
    GaussianSet decoded;
    ASSERT_TRUE(Read(bytes, 2, &decoded).ok());
    ASSERT_EQ(decoded.size(), n);
    for (int group : {kGroupLogScale, kGroupShDc, kGroupShRest}) {
      const size_t distinct = DistinctVectors(decoded, group).size();
      EXPECT_LE(distinct, static_cast<size_t>(size)) << "group " << group;
      EXPECT_GE(distinct, std::min<size_t>(size, 40)) << "group " << group << ": entries used";
    }
    GaussianSet reconstructed;
    ASSERT_TRUE(ReconstructGaussianSet(set, q, &reconstructed).ok());
    EXPECT_EQ(reconstructed.sh, decoded.sh);
    EXPECT_EQ(reconstructed.log_scales, decoded.log_scales);
  }
}

TEST(GaussianSetCodebookTest, EntriesFitTheClusters) {
  // 40 tight clusters and 64 entries: each Gaussian's colour lands near its own cluster, far
  // closer than the 3-bit scalar step of the same range.
  const GaussianSet set = ClusteredSet(4096, 1, 40, 5);
  GaussianQuantization q = Codebooks(64);
  q.codebooks_only_where_they_pay = false;
  GaussianSet decoded;
  ASSERT_TRUE(Read(WriteSet(set, q), 1, &decoded).ok());
  // The decoded order is the coding order: match Gaussians by their positions.
  double squared = 0.0;
  for (size_t j = 0; j < decoded.size(); ++j) {
    size_t best = 0;
    float best_d = INFINITY;
    for (size_t i = 0; i < set.size(); ++i) {
      float d = 0;
      for (int r = 0; r < 3; ++r) {
        const float e = set.positions[3 * i + r] - decoded.positions[3 * j + r];
        d += e * e;
      }
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    for (int r = 0; r < 12; ++r) {
      const double e = double(decoded.sh[12 * j + r]) - set.sh[12 * best + r];
      squared += e * e;
    }
  }
  EXPECT_LT(std::sqrt(squared / (12.0 * decoded.size())), 0.02);
}

TEST(GaussianSetCodebookTest, KeptOnlyWhereItPays) {
  // Clustered colours: the codebook takes fewer bytes at a lower error than 5-bit scalars.
  GaussianQuantization q = Codebooks(64);
  q.log_scale_codebook = 0;
  q.sh_dc_bits = 5;  // rate point r1's
  q.sh_rest_bits = 3;
  const GaussianSet clustered = ClusteredSet(8192, 1, 30, 7);
  const Header kept = ParseHeader(WriteSet(clustered, q), 1);
  EXPECT_EQ(kept.codebook_sizes[kGroupShDc], 64u);
  EXPECT_EQ(kept.codebook_sizes[kGroupShRest], 64u);
  GaussianQuantization scalar = q;
  scalar.sh_dc_codebook = scalar.sh_rest_codebook = 0;
  EXPECT_LT(WriteSet(clustered, q).size(), WriteSet(clustered, scalar).size());
  // Colours uniform in their range: 64 entries err far more than the scalars for the bytes.
  GaussianSet uniform = clustered;
  std::mt19937 rng(9);
  for (float& v : uniform.sh) v = std::uniform_real_distribution<float>(-1, 1)(rng);
  const Header dropped = ParseHeader(WriteSet(uniform, q), 1);
  EXPECT_EQ(dropped.codebook_sizes[kGroupShDc], 0u);
  EXPECT_EQ(dropped.codebook_sizes[kGroupShRest], 0u);
}

TEST(GaussianSetCodebookTest, SmallSetsAndOlderVersionsKeepScalars) {
  GaussianQuantization q = Codebooks(64);
  q.codebooks_only_where_they_pay = false;
  const size_t too_few = static_cast<size_t>(kCodebookMinGaussiansPerEntry) * 64 - 1;
  const GaussianSet small = ClusteredSet(too_few, 1, 10, 11);
  for (uint32_t size : ParseHeader(WriteSet(small, q), 1).codebook_sizes) EXPECT_EQ(size, 0u);
  // A 0.5 set has no codebook_size fields at all, whatever the request.
  q.syntax.codebooks = false;
  const GaussianSet set = ClusteredSet(4096, 1, 10, 12);
  const std::vector<uint8_t> bytes = WriteSet(set, q);
  GaussianSet decoded;
  GaussianSetSyntax v05;
  v05.codebooks = false;
  EXPECT_TRUE(Read(bytes, 1, &decoded, v05).ok());
  EXPECT_EQ(decoded.size(), set.size());
  EXPECT_FALSE(Read(bytes, 1, &decoded).ok());
}

// The set with codebook_size of group slot `slot` replaced by the varuint `size` (the rest of
// the bytes kept, so what follows no longer parses as the writer meant).
std::vector<uint8_t> WithCodebookSize(const std::vector<uint8_t>& bytes, const Header& h, int slot,
                                      uint32_t size) {
  std::vector<uint8_t> out(bytes.begin(), bytes.begin() + h.codebook_offsets[slot]);
  ByteWriter w(&out);
  w.WriteVarUint(size);
  ByteReader r(bytes.data() + h.codebook_offsets[slot], bytes.size() - h.codebook_offsets[slot]);
  uint32_t old;
  EXPECT_TRUE(r.ReadVarUint(&old));
  out.insert(out.end(), bytes.begin() + h.codebook_offsets[slot] + r.position(), bytes.end());
  return out;
}

TEST(GaussianSetCodebookTest, RejectsCodebooksTheSpecDoesNotAllow) {
  const GaussianSet set = ClusteredSet(1024, 1, 10, 13);
  const std::vector<uint8_t> bytes = WriteSet(set, GaussianQuantization());
  const Header h = ParseHeader(bytes, 1);
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 1, &decoded).ok());
  // Size 1, a codebook of positions, rotations or opacities: BITSTREAM; above 4096: LIMIT.
  EXPECT_EQ(Read(WithCodebookSize(bytes, h, kGroupShDc, 1), 1, &decoded).code(), M4D_ERR_BITSTREAM);
  for (int slot : {kGroupPosition, kGroupRotation, kGroupOpacity}) {
    EXPECT_EQ(Read(WithCodebookSize(bytes, h, slot, 2), 1, &decoded).code(), M4D_ERR_BITSTREAM)
        << "group " << slot;
  }
  EXPECT_EQ(Read(WithCodebookSize(bytes, h, kGroupShDc, kMaxCodebookSize + 1), 1, &decoded).code(),
            M4D_ERR_LIMIT);
}

TEST(GaussianSetCodebookTest, RejectsEntriesAboveTheBitsAndIndicesAboveTheSize) {
  const GaussianSet set = ClusteredSet(1024, 0, 10, 17);
  GaussianQuantization q = Codebooks(16);
  q.codebooks_only_where_they_pay = false;
  q.codebook_bits = 4;
  const std::vector<uint8_t> bytes = WriteSet(set, q);
  const Header h = ParseHeader(bytes, 0);
  ASSERT_EQ(h.codebook_sizes[kGroupShDc], 16u);
  GaussianSet decoded;
  ASSERT_TRUE(Read(bytes, 0, &decoded).ok());
  // bits of the DC group one lower: some entry of 0..15 is no longer below 2^3.
  std::vector<uint8_t> fewer_bits = bytes;
  size_t bits_offset = h.codebook_offsets[kGroupOpacity] + 1;  // opacity's codebook_size is 0
  ASSERT_EQ(fewer_bits[bits_offset], 4);
  fewer_bits[bits_offset] = 3;
  EXPECT_EQ(Read(fewer_bits, 0, &decoded).code(), M4D_ERR_BITSTREAM);
  // A codebook of 16 entries read as 8, its last 24 entry values taken as the next fields:
  // whatever follows fails cleanly (the indices up to 15 are not below 8).
  EXPECT_FALSE(Read(WithCodebookSize(bytes, h, kGroupShDc, 8), 0, &decoded).ok());
}

TEST(GaussianSetCodebookTest, WriterRejectsBadCodebookRequests) {
  const GaussianSet set = ClusteredSet(64, 0, 4, 19);
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  for (int size : {-1, 1, 4097}) {
    EXPECT_EQ(WriteGaussianSet(set, Codebooks(size), &w).code(), M4D_ERR_INVALID_ARG) << size;
  }
  GaussianQuantization q;
  for (int bits : {0, 13}) {
    q.codebook_bits = bits;
    EXPECT_EQ(WriteGaussianSet(set, q, &w).code(), M4D_ERR_INVALID_ARG) << bits;
  }
}

}  // namespace
}  // namespace m4d
