#include "encoder/src/layers/octree_positions_writer.h"

#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "sdk/src/common/spec_limits.h"

namespace m4d {
namespace {

// Whether the highest set bit of a is below b's.
bool HighBitBelow(uint32_t a, uint32_t b) { return a < b && a < (a ^ b); }

bool SameNode(const uint32_t* a, const uint32_t* b, int shift) {
  return (a[0] >> shift) == (b[0] >> shift) && (a[1] >> shift) == (b[1] >> shift) &&
         (a[2] >> shift) == (b[2] >> shift);
}

int ChildIndex(const uint32_t* p, int bit) {
  return static_cast<int>((p[0] >> bit & 1) | (p[1] >> bit & 1) << 1 | (p[2] >> bit & 1) << 2);
}

}  // namespace

bool MortonLess(const uint32_t* a, const uint32_t* b) {
  int axis = 2;
  uint32_t differing = a[2] ^ b[2];
  for (int r = 1; r >= 0; --r) {
    if (HighBitBelow(differing, a[r] ^ b[r])) {
      axis = r;
      differing = a[r] ^ b[r];
    }
  }
  return a[axis] < b[axis];
}

Status WriteOctreePositions(const uint32_t* q, size_t n, int bits, RansLayout layout,
                            ByteWriter* out) {
  if (n == 0 || bits < 1 || bits > 24) {
    return Status(M4D_ERR_INVALID_ARG, "WriteOctreePositions: no points or bits outside 1..24");
  }
  std::vector<int32_t> masks;
  for (int d = 0; d < bits; ++d) {
    // A node of level d holds the points sharing their top d bits; points are in Morton
    // order, so each node's points are contiguous.
    const int shift = bits - d, bit = bits - d - 1;
    masks.clear();
    for (size_t i = 0; i < n; ++i) {
      const uint32_t* p = q + 3 * i;
      if (i == 0 || !SameNode(p, p - 3, shift)) masks.push_back(0);
      masks.back() |= 1 << ChildIndex(p, bit);
    }
    M4D_RETURN_IF_ERROR(WriteSymbolBlock(masks.data(), masks.size(), layout, out));
  }
  std::vector<int32_t> low, high;  // Gaussians after the first at each leaf: low + 4096 high
  for (size_t i = 0; i < n; ++i) {
    if (i > 0 && SameNode(q + 3 * i, q + 3 * (i - 1), 0)) {
      if (++low.back() == kOctreeRepeatRadix) {
        low.back() = 0;
        ++high.back();
      }
    } else {
      low.push_back(0);
      high.push_back(0);
    }
  }
  M4D_RETURN_IF_ERROR(WriteSymbolBlock(low.data(), low.size(), layout, out));
  return WriteSymbolBlock(high.data(), high.size(), layout, out);
}

}  // namespace m4d
