#include "sdk/src/decode/motion_application.h"

#include "sdk/src/decode/motion_kernel.h"

namespace m4d {

bool MotionKernelSupported(MotionKernelKind kind) {
  switch (kind) {
    case MotionKernelKind::kBaseline:
      return true;
    case MotionKernelKind::kAvx512:
#if defined(M4D_HAVE_AVX512_KERNEL)
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
#else
      return false;
#endif
  }
  return false;
}

namespace {

// Gaussians per task: a few blocks of lanes, and few enough tasks to balance two threads.
constexpr size_t kGaussiansPerTask = 4096;

void RunKernel(MotionKernelKind kind, const GridConfig& config, const MotionGrid& grid,
               const MlpWeights& mlp, GaussianSet* set, size_t begin, size_t end) {
#if defined(M4D_HAVE_AVX512_KERNEL)
  if (kind == MotionKernelKind::kAvx512) {
    return ApplyMotionAvx512(config, grid, mlp, set, begin, end);
  }
#else
  (void)kind;  // builds without the AVX-512 kernel (other CPUs, WebAssembly)
#endif
  ApplyMotionBaseline(config, grid, mlp, set, begin, end);
}

}  // namespace

void ApplyMotionWith(MotionKernelKind kind, const GridConfig& config, const MotionGrid& grid,
                     const MlpWeights& mlp, GaussianSet* set, ThreadPool* pool) {
  const size_t n = set->size();
  if (pool == nullptr || pool->size() == 1 || n <= kGaussiansPerTask) {
    return RunKernel(kind, config, grid, mlp, set, 0, n);
  }
  ParallelForChunks(pool, n, kGaussiansPerTask, [&](size_t begin, size_t end, int) {
    RunKernel(kind, config, grid, mlp, set, begin, end);
  });
}

void ApplyMotion(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                 GaussianSet* set, ThreadPool* pool) {
  // The CPU cannot change under a running process: decide once.
  static const MotionKernelKind kind = MotionKernelSupported(MotionKernelKind::kAvx512)
                                           ? MotionKernelKind::kAvx512
                                           : MotionKernelKind::kBaseline;
  ApplyMotionWith(kind, config, grid, mlp, set, pool);
}

}  // namespace m4d
