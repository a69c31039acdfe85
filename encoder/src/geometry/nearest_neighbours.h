// NearestNeighbours: the K nearest points of a fixed 3D point set to query points, with a
// kd-tree. Used to size initial Gaussians (mean distance to 3 neighbours) and to smooth the
// static / dynamic classification by a majority vote over 3D neighbourhoods.
//
// Results are exact and well defined: neighbours are ordered by squared distance, ties by
// lower index, so they do not depend on the tree's shape or on the thread count.
#ifndef M4D_ENCODER_GEOMETRY_NEAREST_NEIGHBOURS_H_
#define M4D_ENCODER_GEOMETRY_NEAREST_NEIGHBOURS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// The index of an empty result slot (fewer points than K).
constexpr uint32_t kNoNeighbour = 0xffffffffu;

class NearestNeighbours {
 public:
  // Indexes `count` points (3 floats each; copied). Fails with M4D_ERR_INVALID_ARG for a
  // null array or a non-finite coordinate, M4D_ERR_LIMIT beyond 2^32 - 1 points.
  Status Build(const float* points, size_t count);

  size_t size() const { return indices_.size(); }

  // The k nearest points to `query`, nearest first, skipping point `exclude` (kNoNeighbour:
  // skip none). Writes k indices and squared distances; slots beyond the points available
  // (or all slots, for a non-finite query) get kNoNeighbour and +infinity.
  void Query(const float query[3], int k, uint32_t exclude, uint32_t* indices,
             float* squared_distances) const;

  // Query for each of `count` query points (3 floats each) into k slots per query, on
  // `threads` threads (0: the hardware's). With exclude_same_index, query i skips point i
  // (queries are the indexed points themselves). squared_distances may be null.
  void QueryAll(const float* queries, size_t count, int k, bool exclude_same_index, int threads,
                uint32_t* indices, float* squared_distances) const;

 private:
  struct Node {
    uint32_t begin = 0, end = 0;   // range of sorted points
    uint32_t left = 0, right = 0;  // children; 0 for a leaf (the root is never a child)
    float split = 0;
    int axis = -1;  // -1: leaf
  };

  uint32_t BuildNode(uint32_t begin, uint32_t end);

  std::vector<float> points_;      // 3 per point, in tree order
  std::vector<uint32_t> indices_;  // original index of each point in tree order
  std::vector<Node> nodes_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_GEOMETRY_NEAREST_NEIGHBOURS_H_
