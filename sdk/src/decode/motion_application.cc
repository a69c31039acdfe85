#include "decode/motion_application.h"

#include "decode/motion_kernel.h"

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

void ApplyMotionWith(MotionKernelKind kind, const GridConfig& config, const MotionGrid& grid,
                     const MlpWeights& mlp, GaussianSet* set) {
#if defined(M4D_HAVE_AVX512_KERNEL)
  if (kind == MotionKernelKind::kAvx512) return ApplyMotionAvx512(config, grid, mlp, set);
#endif
  ApplyMotionBaseline(config, grid, mlp, set);
}

void ApplyMotion(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                 GaussianSet* set) {
  // The CPU cannot change under a running process: decide once.
  static const MotionKernelKind kind = MotionKernelSupported(MotionKernelKind::kAvx512)
                                           ? MotionKernelKind::kAvx512
                                           : MotionKernelKind::kBaseline;
  ApplyMotionWith(kind, config, grid, mlp, set);
}

}  // namespace m4d
