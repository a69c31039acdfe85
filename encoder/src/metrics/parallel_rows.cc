#include "encoder/src/metrics/parallel_rows.h"

#include <algorithm>
#include <thread>
#include <vector>

namespace m4d {

void ParallelForRows(int rows, size_t row_samples, const std::function<void(int, int)>& fn) {
  constexpr size_t kMinSamplesPerThread = size_t{1} << 14;
  const size_t by_work = rows * row_samples / kMinSamplesPerThread;
  const size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  const int threads = static_cast<int>(
      std::max<size_t>(1, std::min({hardware, by_work, static_cast<size_t>(rows)})));
  std::vector<std::thread> workers;
  workers.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) {
    workers.emplace_back(fn, rows * t / threads, rows * (t + 1) / threads);
  }
  fn(0, rows / threads);
  for (std::thread& worker : workers) worker.join();
}

}  // namespace m4d
