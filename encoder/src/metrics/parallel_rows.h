// Splitting per-row image work across threads.
#ifndef M4D_ENCODER_METRICS_PARALLEL_ROWS_H_
#define M4D_ENCODER_METRICS_PARALLEL_ROWS_H_

#include <cstddef>
#include <functional>

namespace m4d {

// Calls fn(begin, end) on contiguous ranges that cover rows [0, rows) once, each range on its
// own thread (the caller's thread takes the first), and returns when all are done. Uses up to
// std::thread::hardware_concurrency() threads, fewer when a thread would get less than about
// 16k samples (rows * row_samples in total), since starting a thread costs tens of
// microseconds. Results must not depend on the split: fn writes only to its rows.
void ParallelForRows(int rows, size_t row_samples, const std::function<void(int, int)>& fn);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_PARALLEL_ROWS_H_
