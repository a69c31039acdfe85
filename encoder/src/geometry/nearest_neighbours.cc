#include "encoder/src/geometry/nearest_neighbours.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sdk/src/common/thread_pool.h"

namespace m4d {
namespace {

constexpr uint32_t kLeafSize = 8;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The best k candidates so far, sorted by (squared distance, index).
class Candidates {
 public:
  Candidates(int k, uint32_t* indices, float* distances)
      : k_(k), indices_(indices), distances_(distances) {
    std::fill(indices, indices + k, kNoNeighbour);
    std::fill(distances, distances + k, kInfinity);
  }
  bool full() const { return size_ == k_; }
  float worst() const { return full() ? distances_[k_ - 1] : kInfinity; }

  void Offer(uint32_t index, float d2) {
    if (full() && !Before(d2, index, distances_[k_ - 1], indices_[k_ - 1])) return;
    int pos = full() ? k_ - 1 : size_++;
    while (pos > 0 && Before(d2, index, distances_[pos - 1], indices_[pos - 1])) {
      distances_[pos] = distances_[pos - 1];
      indices_[pos] = indices_[pos - 1];
      --pos;
    }
    distances_[pos] = d2;
    indices_[pos] = index;
  }

 private:
  static bool Before(float d2, uint32_t i, float other_d2, uint32_t other_i) {
    return d2 < other_d2 || (d2 == other_d2 && i < other_i);
  }
  int k_;
  int size_ = 0;
  uint32_t* indices_;
  float* distances_;
};

}  // namespace

Status NearestNeighbours::Build(const float* points, size_t count) {
  if (points == nullptr && count > 0) {
    return Status(M4D_ERR_INVALID_ARG, "nearest neighbours: null points");
  }
  if (count >= kNoNeighbour) return LimitError("nearest neighbours: too many points");
  for (size_t i = 0; i < 3 * count; ++i) {
    if (!std::isfinite(points[i])) {
      return Status(M4D_ERR_INVALID_ARG,
                    "nearest neighbours: point " + std::to_string(i / 3) + " is not finite");
    }
  }
  points_.assign(points, points + 3 * count);
  indices_.resize(count);
  for (size_t i = 0; i < count; ++i) indices_[i] = static_cast<uint32_t>(i);
  nodes_.clear();
  if (count > 0) BuildNode(0, static_cast<uint32_t>(count));
  // Store the points in tree order so that leaves read contiguous memory.
  std::vector<float> sorted(3 * count);
  for (size_t i = 0; i < count; ++i) {
    std::copy_n(&points_[3 * size_t{indices_[i]}], 3, &sorted[3 * i]);
  }
  points_.swap(sorted);
  return Status::Ok();
}

uint32_t NearestNeighbours::BuildNode(uint32_t begin, uint32_t end) {
  const uint32_t id = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  nodes_[id].begin = begin;
  nodes_[id].end = end;
  if (end - begin <= kLeafSize) return id;
  // Split the widest axis of the range's bounding box at the median.
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = points_[3 * size_t{indices_[begin]} + a];
  for (uint32_t i = begin; i < end; ++i) {
    for (int a = 0; a < 3; ++a) {
      const float v = points_[3 * size_t{indices_[i]} + a];
      lo[a] = std::min(lo[a], v);
      hi[a] = std::max(hi[a], v);
    }
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  }
  const uint32_t mid = begin + (end - begin) / 2;
  const float* p = points_.data();
  std::nth_element(indices_.begin() + begin, indices_.begin() + mid, indices_.begin() + end,
                   [p, axis](uint32_t a, uint32_t b) {
                     const float va = p[3 * size_t{a} + axis], vb = p[3 * size_t{b} + axis];
                     return va < vb || (va == vb && a < b);
                   });
  const float split = points_[3 * size_t{indices_[mid]} + axis];
  const uint32_t left = BuildNode(begin, mid);
  const uint32_t right = BuildNode(mid, end);
  nodes_[id].axis = axis;
  nodes_[id].split = split;
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

void NearestNeighbours::Query(const float query[3], int k, uint32_t exclude, uint32_t* indices,
                              float* squared_distances) const {
  if (k <= 0) return;
  Candidates best(k, indices, squared_distances);
  if (nodes_.empty() || !std::isfinite(query[0]) || !std::isfinite(query[1]) ||
      !std::isfinite(query[2])) {
    return;
  }
  // Depth-first, nearer child first; a far child is kept with the lower bound of its
  // distance (to the splitting plane) and skipped if the k-th best is already closer.
  struct Pending {
    uint32_t node;
    float bound;
  };
  Pending stack[64];
  int top = 0;
  stack[top++] = {0, 0.0f};
  while (top > 0) {
    const Pending item = stack[--top];
    if (item.bound > best.worst()) continue;
    const Node* node = &nodes_[item.node];
    while (node->axis >= 0) {
      const float diff = query[node->axis] - node->split;
      const uint32_t near = diff < 0 ? node->left : node->right;
      const uint32_t far = diff < 0 ? node->right : node->left;
      stack[top++] = {far, diff * diff};
      node = &nodes_[near];
    }
    for (uint32_t i = node->begin; i < node->end; ++i) {
      const uint32_t index = indices_[i];
      if (index == exclude) continue;
      const float* p = &points_[3 * size_t{i}];
      const float dx = p[0] - query[0], dy = p[1] - query[1], dz = p[2] - query[2];
      best.Offer(index, dx * dx + dy * dy + dz * dz);
    }
  }
}

void NearestNeighbours::QueryAll(const float* queries, size_t count, int k, bool exclude_same_index,
                                 int threads, uint32_t* indices, float* squared_distances) const {
  if (k <= 0 || count == 0) return;
  ThreadPool pool(threads);
  ParallelForChunks(&pool, count, 1024, [&](size_t begin, size_t end, int) {
    std::vector<float> scratch(squared_distances ? 0 : static_cast<size_t>(k));
    for (size_t q = begin; q < end; ++q) {
      const size_t slot = q * static_cast<size_t>(k);
      float* d2 = squared_distances ? squared_distances + slot : scratch.data();
      const uint32_t exclude = exclude_same_index ? static_cast<uint32_t>(q) : kNoNeighbour;
      Query(&queries[3 * q], k, exclude, indices + slot, d2);
    }
  });
}

}  // namespace m4d
