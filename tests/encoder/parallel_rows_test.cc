// Row splitting across threads (metrics/parallel_rows.h).

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <utility>
#include <vector>

#include "encoder/src/metrics/parallel_rows.h"

namespace m4d {
namespace {

TEST(ParallelRowsTest, CoversEveryRowOnceInContiguousRanges) {
  for (int rows : {0, 1, 2, 7, 480}) {
    for (size_t row_samples : {size_t{1}, size_t{3 * 640}, size_t{1} << 20}) {
      std::vector<std::atomic<int>> visits(rows);
      std::mutex mutex;
      std::vector<std::pair<int, int>> ranges;
      ParallelForRows(rows, row_samples, [&](int begin, int end) {
        for (int r = begin; r < end; ++r) visits[r]++;
        std::lock_guard<std::mutex> lock(mutex);
        ranges.emplace_back(begin, end);
      });
      for (int r = 0; r < rows; ++r) ASSERT_EQ(visits[r].load(), 1) << rows << " rows";
      for (const auto& range : ranges) EXPECT_LE(range.first, range.second);
      EXPECT_GE(ranges.size(), 1u);
      if (rows * row_samples < (size_t{1} << 14)) {
        EXPECT_EQ(ranges.size(), 1u) << "small jobs stay on the calling thread";
      }
    }
  }
}

}  // namespace
}  // namespace m4d
