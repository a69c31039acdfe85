// octree_positions() (bitstream-spec 5.6): the writer's octree decodes to the same quantized
// positions in the same (Morton) order at every depth, and the reader refuses malformed trees.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "encoder/src/layers/octree_positions_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/layers/octree_positions.h"

namespace m4d {
namespace {

// n random points below 2^bits, every fifth a copy of the one before, in Morton order.
std::vector<uint32_t> MortonSortedPoints(size_t n, int bits, uint32_t seed) {
  std::mt19937 rng(seed);
  const uint32_t mask = bits == 32 ? ~0u : (1u << bits) - 1;
  std::vector<uint32_t> q(3 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int r = 0; r < 3; ++r) q[3 * i + r] = i % 5 == 4 ? q[3 * (i - 1) + r] : rng() & mask;
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return MortonLess(&q[3 * a], &q[3 * b]); });
  std::vector<uint32_t> sorted(3 * n);
  for (size_t i = 0; i < n; ++i) std::copy_n(&q[3 * order[i]], 3, &sorted[3 * i]);
  return sorted;
}

Status RoundTrip(const std::vector<uint32_t>& q, int bits, std::vector<uint32_t>* decoded) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  M4D_RETURN_IF_ERROR(
      WriteOctreePositions(q.data(), q.size() / 3, bits, RansLayout::kInterleaved, &writer));
  ByteReader reader(bytes.data(), bytes.size());
  decoded->assign(q.size(), 0);
  M4D_RETURN_IF_ERROR(ReadOctreePositions(&reader, RansLayout::kInterleaved,
                                          static_cast<uint32_t>(q.size() / 3), bits,
                                          decoded->data()));
  EXPECT_EQ(reader.remaining(), 0u);
  return Status::Ok();
}

// The 3 * 21-bit Morton key (z's bit most significant at each level).
uint64_t MortonKey(const uint32_t* p) {
  uint64_t key = 0;
  for (int b = 0; b < 21; ++b) {
    for (int r = 0; r < 3; ++r) key |= static_cast<uint64_t>(p[r] >> b & 1) << (3 * b + r);
  }
  return key;
}

TEST(OctreePositionsTest, MortonLessIsTheOrderOfInterleavedBits) {
  const std::vector<uint32_t> q = MortonSortedPoints(2000, 21, 1);
  for (size_t i = 1; i < 2000; ++i) {
    EXPECT_LE(MortonKey(&q[3 * (i - 1)]), MortonKey(&q[3 * i])) << i;
  }
  const uint32_t a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {0, 0, 1}, d[3] = {7, 7, 0};
  EXPECT_TRUE(MortonLess(a, b));
  EXPECT_TRUE(MortonLess(b, c));
  EXPECT_TRUE(MortonLess(c, d));  // z bit 0 ranks below x and y bit 2
  EXPECT_FALSE(MortonLess(d, c));
  EXPECT_FALSE(MortonLess(a, a));
}

TEST(OctreePositionsTest, DecodesTheWrittenPositionsInOrderAtEveryDepth) {
  for (int bits : {1, 2, 5, 12, 16, 21, 24}) {
    const std::vector<uint32_t> q = MortonSortedPoints(3000, bits, static_cast<uint32_t>(bits));
    std::vector<uint32_t> decoded;
    ASSERT_TRUE(RoundTrip(q, bits, &decoded).ok()) << bits;
    EXPECT_EQ(decoded, q) << bits;
  }
}

TEST(OctreePositionsTest, LeavesOfMoreThanTheRadixRoundTrip) {
  // 5000 Gaussians at (0, 0, 0) then one at (1, 1, 1): repeats 4999 = 903 + 4096 * 1.
  std::vector<uint32_t> q(3 * 5001, 0);
  std::fill(q.end() - 3, q.end(), 1u);
  std::vector<uint32_t> decoded;
  ASSERT_TRUE(RoundTrip(q, 1, &decoded).ok());
  EXPECT_EQ(decoded, q);
}

// Bytes of an octree of depth 1 over `count` Gaussians with the given mask and repeats.
std::vector<uint8_t> DepthOneOctree(int32_t mask, const std::vector<int32_t>& low,
                                    const std::vector<int32_t>& high) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  EXPECT_TRUE(WriteSymbolBlock(&mask, 1, RansLayout::kInterleaved, &writer).ok());
  EXPECT_TRUE(WriteSymbolBlock(low.data(), low.size(), RansLayout::kInterleaved, &writer).ok());
  EXPECT_TRUE(WriteSymbolBlock(high.data(), high.size(), RansLayout::kInterleaved, &writer).ok());
  return bytes;
}

Status Read(const std::vector<uint8_t>& bytes, uint32_t count) {
  ByteReader reader(bytes.data(), bytes.size());
  std::vector<uint32_t> q(3 * static_cast<size_t>(count));
  return ReadOctreePositions(&reader, RansLayout::kInterleaved, count, 1, q.data());
}

TEST(OctreePositionsTest, RefusesMalformedTrees) {
  EXPECT_TRUE(Read(DepthOneOctree(0b11, {0, 1}, {0, 0}), 3).ok());
  // A mask of 0: a node without children.
  EXPECT_EQ(Read(DepthOneOctree(0, {0}, {0}), 3).code(), M4D_ERR_BITSTREAM);
  // More nodes (2) than Gaussians (1).
  EXPECT_EQ(Read(DepthOneOctree(0b11, {0, 0}, {0, 0}), 1).code(), M4D_ERR_BITSTREAM);
  // Leaves holding 2 Gaussians of 3.
  EXPECT_EQ(Read(DepthOneOctree(0b11, {0, 0}, {0, 0}), 3).code(), M4D_ERR_BITSTREAM);
  // A high repeat above (count - 1) / 4096.
  EXPECT_EQ(Read(DepthOneOctree(0b1, {2}, {1}), 3).code(), M4D_ERR_BITSTREAM);
  // Cut short.
  std::vector<uint8_t> cut = DepthOneOctree(0b11, {0, 1}, {0, 0});
  cut.pop_back();
  EXPECT_EQ(Read(cut, 3).code(), M4D_ERR_BITSTREAM);
  // The writer refuses what has no octree.
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  const uint32_t point[3] = {0, 0, 0};
  EXPECT_EQ(WriteOctreePositions(point, 1, 0, RansLayout::kInterleaved, &writer).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(WriteOctreePositions(point, 0, 4, RansLayout::kInterleaved, &writer).code(),
            M4D_ERR_INVALID_ARG);
}

}  // namespace
}  // namespace m4d
