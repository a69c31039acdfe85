#include "sdk/src/layers/octree_positions.h"

#include <string>
#include <vector>

#include "sdk/src/common/spec_limits.h"

namespace m4d {
namespace {

Status OctreeError(const std::string& what) {
  return Status(M4D_ERR_BITSTREAM, "octree_positions: " + what);
}

}  // namespace

Status ReadOctreePositions(ByteReader* reader, RansLayout layout, uint32_t count, int bits,
                           uint32_t* q) {
  // Node coordinates of the current level (x y z, the top d bits of their points'), in order.
  std::vector<uint32_t> nodes = {0, 0, 0}, children;
  std::vector<int32_t> masks;
  uint32_t num_nodes = 1;
  for (int d = 0; d < bits; ++d) {
    masks.resize(num_nodes);
    M4D_RETURN_IF_ERROR(ReadSymbolBlock(reader, layout, num_nodes, 1, 255, masks.data()));
    uint32_t next = 0;
    for (int32_t m : masks) next += static_cast<uint32_t>(__builtin_popcount(m));
    if (next > count) {
      return OctreeError("level " + std::to_string(d + 1) + " has " + std::to_string(next) +
                         " nodes, more than the " + std::to_string(count) + " Gaussians");
    }
    children.resize(3 * static_cast<size_t>(next));
    uint32_t* child = children.data();
    for (uint32_t k = 0; k < num_nodes; ++k) {
      const uint32_t* node = &nodes[3 * static_cast<size_t>(k)];
      for (int c = 0; c < 8; ++c) {
        if (!(masks[k] >> c & 1)) continue;
        *child++ = node[0] << 1 | (c & 1);
        *child++ = node[1] << 1 | (c >> 1 & 1);
        *child++ = node[2] << 1 | (c >> 2 & 1);
      }
    }
    nodes.swap(children);
    num_nodes = next;
  }
  // Gaussians after the first at each leaf, low + kOctreeRepeatRadix * high.
  std::vector<int32_t> repeats(num_nodes), high(num_nodes);
  M4D_RETURN_IF_ERROR(
      ReadSymbolBlock(reader, layout, num_nodes, 0, kOctreeRepeatRadix - 1, repeats.data()));
  M4D_RETURN_IF_ERROR(ReadSymbolBlock(reader, layout, num_nodes, 0,
                                      static_cast<int32_t>((count - 1) / kOctreeRepeatRadix),
                                      high.data()));
  uint64_t total = 0;
  for (uint32_t k = 0; k < num_nodes; ++k) {
    repeats[k] += kOctreeRepeatRadix * high[k];
    total += static_cast<uint64_t>(repeats[k]) + 1;
  }
  if (total != count) {
    return OctreeError("its leaves hold " + std::to_string(total) + " Gaussians, not " +
                       std::to_string(count));
  }
  for (uint32_t k = 0; k < num_nodes; ++k) {
    for (int32_t i = 0; i <= repeats[k]; ++i, q += 3) {
      q[0] = nodes[3 * static_cast<size_t>(k)];
      q[1] = nodes[3 * static_cast<size_t>(k) + 1];
      q[2] = nodes[3 * static_cast<size_t>(k) + 2];
    }
  }
  return Status::Ok();
}

}  // namespace m4d
