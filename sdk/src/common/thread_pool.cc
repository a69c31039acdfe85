#include "sdk/src/common/thread_pool.h"

#include <algorithm>
#include <system_error>

namespace m4d {

ThreadPool::ThreadPool(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(threads, 1);
  workers_.reserve(static_cast<size_t>(threads - 1));
  for (int w = 1; w < threads; ++w) {
    try {
      workers_.emplace_back(&ThreadPool::WorkerLoop, this, w);
    } catch (const std::system_error&) {
      break;  // run with the workers we have
    }
  }
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::RunTasks(int worker) {
  const std::function<void(size_t, int)>& body = *body_;
  for (size_t task = next_.fetch_add(1); task < count_; task = next_.fetch_add(1)) {
    body(task, worker);
  }
}

void ThreadPool::WorkerLoop(int worker) {
  size_t seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    RunTasks(worker);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) finished_.notify_one();
    }
  }
}

void ThreadPool::Run(size_t count, const std::function<void(size_t, int)>& body) {
  if (count == 0) return;
  if (workers_.empty() || count == 1) {
    for (size_t task = 0; task < count; ++task) body(task, 0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    body_ = &body;
    count_ = count;
    next_.store(0);
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  wake_.notify_all();
  RunTasks(0);
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return busy_ == 0; });
  body_ = nullptr;
}

void ParallelForChunks(ThreadPool* pool, size_t n, size_t chunk,
                       const std::function<void(size_t, size_t, int)>& body) {
  chunk = std::max<size_t>(chunk, 1);
  const size_t chunks = (n + chunk - 1) / chunk;
  pool->Run(chunks, [&](size_t c, int worker) {
    const size_t begin = c * chunk;
    body(begin, std::min(n, begin + chunk), worker);
  });
}

}  // namespace m4d
