// ThreadPool: a fixed set of persistent worker threads for parallel loops (tiles, chunks of
// Gaussians). The calling thread works too, so a pool of size 1 runs everything inline and
// never creates a thread. Tasks are claimed one at a time from a shared counter, so a task
// should be a sizeable piece of work (a tile, a few hundred Gaussians), not a pixel.
#ifndef M4D_SDK_COMMON_THREAD_POOL_H_
#define M4D_SDK_COMMON_THREAD_POOL_H_

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace m4d {

class ThreadPool {
 public:
  // threads: total workers including the caller; 0 means std::thread::hardware_concurrency().
  // If the system refuses to start a thread the pool keeps the ones it has.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  // Number of workers (>= 1). Worker indices passed to bodies are below this.
  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls body(task, worker) once for every task in [0, count) and returns when all have
  // finished. The caller is worker 0. body must not throw. One Run at a time per pool.
  void Run(size_t count, const std::function<void(size_t task, int worker)>& body);

 private:
  void WorkerLoop(int worker);
  void RunTasks(int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable finished_;
  // Guarded by mutex_: the current job and its generation (bumped per Run).
  const std::function<void(size_t, int)>* body_ = nullptr;
  size_t count_ = 0;
  size_t generation_ = 0;
  int busy_ = 0;
  bool stop_ = false;
  std::atomic<size_t> next_{0};
};

// Runs body(begin, end, worker) over [0, n) in chunks of `chunk` items (the last may be
// shorter). For per-Gaussian loops.
void ParallelForChunks(ThreadPool* pool, size_t n, size_t chunk,
                       const std::function<void(size_t begin, size_t end, int worker)>& body);

}  // namespace m4d

#endif  // M4D_SDK_COMMON_THREAD_POOL_H_
