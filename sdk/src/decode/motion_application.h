// Motion application (bitstream-spec 6.3; paper section 3.3): trilinear lookup of the motion
// grid at each dynamic Gaussian, the shared MLP, then translation and quaternion composition.
// Normative float code: built with -ffp-contract=off; vectorised across Gaussians only.
#ifndef M4D_SDK_DECODE_MOTION_APPLICATION_H_
#define M4D_SDK_DECODE_MOTION_APPLICATION_H_

#include "sdk/src/common/thread_pool.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_config.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {

// Builds of the motion kernel; every one gives bit-identical results.
enum class MotionKernelKind { kBaseline, kAvx512 };

// True when this build has the kernel and the CPU runs it.
bool MotionKernelSupported(MotionKernelKind kind);

// Moves every Gaussian of *set in place (positions and rotations), as spec 6.3 says, with the
// fastest supported kernel; spread over `pool` when given (each Gaussian is computed alone, so
// the result is the same at any thread count).
void ApplyMotion(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                 GaussianSet* set, ThreadPool* pool = nullptr);

// The same with a given kernel, which must be supported (for tests and benchmarks).
void ApplyMotionWith(MotionKernelKind kind, const GridConfig& config, const MotionGrid& grid,
                     const MlpWeights& mlp, GaussianSet* set, ThreadPool* pool = nullptr);

}  // namespace m4d

#endif  // M4D_SDK_DECODE_MOTION_APPLICATION_H_
