// The kd-tree K-nearest-neighbour search (geometry/nearest_neighbours.h) against brute force.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "encoder/src/geometry/nearest_neighbours.h"

namespace m4d {
namespace {

std::vector<float> RandomPoints(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> p(3 * n);
  for (float& v : p) v = unit(rng);
  // Clusters and duplicates, which stress ties and unbalanced cells.
  for (size_t i = 0; i < n / 10; ++i) {
    for (int a = 0; a < 3; ++a) p[3 * (n - 1 - i) + a] = p[3 * i + a] * (i % 2 ? 1.0f : 0.01f);
  }
  return p;
}

// Brute force: (squared distance, index) pairs, sorted.
std::vector<std::pair<float, uint32_t>> BruteForce(const std::vector<float>& points, const float* q,
                                                   int k, uint32_t exclude) {
  std::vector<std::pair<float, uint32_t>> all;
  for (size_t i = 0; i < points.size() / 3; ++i) {
    if (i == exclude) continue;
    const float dx = points[3 * i] - q[0], dy = points[3 * i + 1] - q[1],
                dz = points[3 * i + 2] - q[2];
    all.emplace_back(dx * dx + dy * dy + dz * dz, static_cast<uint32_t>(i));
  }
  std::sort(all.begin(), all.end());
  all.resize(std::min(all.size(), static_cast<size_t>(k)));
  return all;
}

// Distances must match; indices too, except where a distance is tied (within rounding).
void ExpectMatches(const std::vector<std::pair<float, uint32_t>>& expected, const uint32_t* indices,
                   const float* d2, int k) {
  for (int j = 0; j < k; ++j) {
    if (j >= static_cast<int>(expected.size())) {
      EXPECT_EQ(indices[j], kNoNeighbour);
      EXPECT_EQ(d2[j], std::numeric_limits<float>::infinity());
      continue;
    }
    EXPECT_NEAR(d2[j], expected[j].first, 1e-6f * (1.0f + expected[j].first));
    const bool tied = (j > 0 && expected[j].first - expected[j - 1].first < 1e-6f) ||
                      (j + 1 < static_cast<int>(expected.size()) &&
                       expected[j + 1].first - expected[j].first < 1e-6f);
    if (!tied) {
      EXPECT_EQ(indices[j], expected[j].second) << "slot " << j;
    }
  }
}

TEST(NearestNeighboursTest, MatchesBruteForceForQueries) {
  const std::vector<float> points = RandomPoints(3000, 1);
  NearestNeighbours knn;
  ASSERT_TRUE(knn.Build(points.data(), points.size() / 3).ok());
  EXPECT_EQ(knn.size(), 3000u);
  const std::vector<float> queries = RandomPoints(200, 2);
  for (int k : {1, 5, 17}) {
    std::vector<uint32_t> idx(200 * k);
    std::vector<float> d2(200 * k);
    knn.QueryAll(queries.data(), 200, k, false, 2, idx.data(), d2.data());
    for (size_t q = 0; q < 200; ++q) {
      ExpectMatches(BruteForce(points, &queries[3 * q], k, kNoNeighbour), &idx[q * k], &d2[q * k],
                    k);
    }
  }
}

TEST(NearestNeighboursTest, ExcludesSelfAmongItsOwnPoints) {
  const std::vector<float> points = RandomPoints(1000, 3);
  NearestNeighbours knn;
  ASSERT_TRUE(knn.Build(points.data(), 1000).ok());
  constexpr int k = 5;
  std::vector<uint32_t> idx(1000 * k);
  std::vector<float> d2(1000 * k);
  knn.QueryAll(points.data(), 1000, k, true, 0, idx.data(), d2.data());
  for (uint32_t q = 0; q < 1000; ++q) {
    ExpectMatches(BruteForce(points, &points[3 * q], k, q), &idx[q * k], &d2[q * k], k);
    for (int j = 0; j < k; ++j) EXPECT_NE(idx[q * k + j], q);
  }
}

TEST(NearestNeighboursTest, ResultsDoNotDependOnThreads) {
  const std::vector<float> points = RandomPoints(5000, 4);
  NearestNeighbours knn;
  ASSERT_TRUE(knn.Build(points.data(), 5000).ok());
  std::vector<uint32_t> one(5000 * 3), two(5000 * 3);
  knn.QueryAll(points.data(), 5000, 3, true, 1, one.data(), nullptr);
  knn.QueryAll(points.data(), 5000, 3, true, 2, two.data(), nullptr);
  EXPECT_EQ(one, two);
}

TEST(NearestNeighboursTest, FewerPointsThanKLeaveEmptySlots) {
  const float points[6] = {0, 0, 0, 1, 0, 0};
  NearestNeighbours knn;
  ASSERT_TRUE(knn.Build(points, 2).ok());
  uint32_t idx[4];
  float d2[4];
  const float q[3] = {0.9f, 0, 0};
  knn.Query(q, 4, kNoNeighbour, idx, d2);
  EXPECT_EQ(idx[0], 1u);
  EXPECT_EQ(idx[1], 0u);
  EXPECT_EQ(idx[2], kNoNeighbour);
  EXPECT_EQ(idx[3], kNoNeighbour);
  EXPECT_FLOAT_EQ(d2[1], 0.81f);
  knn.Query(q, 4, 1, idx, d2);  // excluding point 1
  EXPECT_EQ(idx[0], 0u);
  EXPECT_EQ(idx[1], kNoNeighbour);
}

TEST(NearestNeighboursTest, EmptySetAndBadInput) {
  NearestNeighbours knn;
  ASSERT_TRUE(knn.Build(nullptr, 0).ok());
  uint32_t idx[2];
  float d2[2];
  const float q[3] = {0, 0, 0};
  knn.Query(q, 2, kNoNeighbour, idx, d2);
  EXPECT_EQ(idx[0], kNoNeighbour);

  EXPECT_EQ(knn.Build(nullptr, 3).code(), M4D_ERR_INVALID_ARG);
  const float bad[6] = {0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 0};
  EXPECT_EQ(knn.Build(bad, 2).code(), M4D_ERR_INVALID_ARG);

  const float good[3] = {1, 2, 3};
  ASSERT_TRUE(knn.Build(good, 1).ok());
  const float nan_query[3] = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
  knn.Query(nan_query, 2, kNoNeighbour, idx, d2);
  EXPECT_EQ(idx[0], kNoNeighbour);
  EXPECT_EQ(idx[1], kNoNeighbour);
}

}  // namespace
}  // namespace m4d
