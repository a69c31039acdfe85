// The merge of compensated Gaussians (bitstream-spec 6.4) on small sets whose order is worked
// out by hand: added Gaussians fill holes in increasing order, surplus ones are appended, and
// surplus holes take the last Gaussian, largest hole first.
#include <gtest/gtest.h>

#include <vector>

#include "sdk/src/decode/compensation_merge.h"

namespace m4d {
namespace {

// A set whose Gaussian i carries the tag ids[i] in every attribute.
GaussianSet Tagged(const std::vector<float>& ids, int sh_degree) {
  GaussianSet set;
  set.sh_degree = sh_degree;
  set.Resize(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    for (int k = 0; k < 3; ++k) set.positions[3 * i + k] = ids[i];
    for (int k = 0; k < 3; ++k) set.log_scales[3 * i + k] = -ids[i];
    for (int k = 0; k < 4; ++k) set.rotations[4 * i + k] = ids[i] + k;
    set.opacity_logits[i] = 2 * ids[i];
    for (int k = 0; k < set.sh_floats(); ++k) set.sh[set.sh_floats() * i + k] = ids[i] * 10 + k;
  }
  return set;
}

void ExpectOrder(const std::vector<int32_t>& removed, const std::vector<float>& added_ids, size_t n,
                 const std::vector<float>& expected) {
  std::vector<float> ids;
  for (size_t i = 0; i < n; ++i) ids.push_back(static_cast<float>(i));
  GaussianSet set = Tagged(ids, 1);
  MergeCompensation(removed.empty() ? nullptr : removed.data(), Tagged(added_ids, 1), &set);
  const GaussianSet want = Tagged(expected, 1);
  ASSERT_EQ(set.size(), expected.size());
  EXPECT_EQ(set.positions, want.positions);
  EXPECT_EQ(set.log_scales, want.log_scales);
  EXPECT_EQ(set.rotations, want.rotations);
  EXPECT_EQ(set.opacity_logits, want.opacity_logits);
  EXPECT_EQ(set.sh, want.sh);
}

TEST(CompensationMergeTest, AddedFillHolesThenAppend) {
  ExpectOrder({0, 1, 0, 1, 0, 0}, {100, 101, 102}, 6, {0, 100, 2, 101, 4, 5, 102});
}

TEST(CompensationMergeTest, EqualCountsReplaceInPlace) {
  ExpectOrder({1, 0, 0, 1}, {100, 101}, 4, {100, 1, 2, 101});
}

TEST(CompensationMergeTest, SurplusHolesTakeTheLastGaussian) {
  // Hole 1 gets 100; hole 5 is the last Gaussian (dropped); Gaussian 4 moves into hole 3.
  ExpectOrder({0, 1, 0, 1, 0, 1}, {100}, 6, {0, 100, 2, 4});
  // Hole 4 is last (dropped), then Gaussian 3 moves into hole 0.
  ExpectOrder({1, 0, 0, 0, 1}, {}, 5, {3, 1, 2});
  // Holes 5 and 4 are dropped in turn, Gaussian 3 fills hole 2, then moves on into hole 0.
  ExpectOrder({1, 0, 1, 0, 1, 1}, {}, 6, {3, 1});
}

TEST(CompensationMergeTest, RemoveAllAndAddOnly) {
  ExpectOrder({1, 1, 1}, {}, 3, {});
  ExpectOrder({1, 1, 1}, {7, 8, 9, 10}, 3, {7, 8, 9, 10});
  ExpectOrder({}, {100, 101}, 2, {0, 1, 100, 101});
  ExpectOrder({}, {}, 2, {0, 1});
}

}  // namespace
}  // namespace m4d
