// Entry points of the motion kernel builds (see motion_kernel.cc); callers use ApplyMotion
// (motion_application.h), which picks the fastest one the CPU runs.
#ifndef M4D_SDK_DECODE_MOTION_KERNEL_H_
#define M4D_SDK_DECODE_MOTION_KERNEL_H_

#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_config.h"
#include "sdk/src/layers/motion_grid.h"

#ifndef M4D_MOTION_KERNEL_NAME
#define M4D_MOTION_KERNEL_NAME ApplyMotionBaseline
#endif

namespace m4d {

// Each moves Gaussians [begin, end) of *set; the others are left untouched.
void ApplyMotionBaseline(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                         GaussianSet* set, size_t begin, size_t end);
// Only in x86-64 builds with M4D_HAVE_AVX512_KERNEL; only on CPUs with AVX-512 F/VL/DQ/BW.
void ApplyMotionAvx512(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                       GaussianSet* set, size_t begin, size_t end);

}  // namespace m4d

#endif  // M4D_SDK_DECODE_MOTION_KERNEL_H_
