// GaussianSet: the decoded state of one layer, attribute by attribute (structure of arrays).
// Values are stored before activation, as coded: log scales, opacity logits, unnormalised
// quaternions (w, x, y, z) and SH coefficients ordered [gaussian][k][channel].
#ifndef M4D_SDK_LAYERS_GAUSSIAN_SET_H_
#define M4D_SDK_LAYERS_GAUSSIAN_SET_H_

#include <cstddef>
#include <cstdint>

#include "sdk/src/common/hooked_allocator.h"

namespace m4d {

inline int ShCoefficients(int sh_degree) { return (sh_degree + 1) * (sh_degree + 1); }

struct GaussianSet {
  GaussianSet() = default;
  explicit GaussianSet(const M4dAllocator* hooks)
      : positions(HookedAllocator<float>(hooks)),
        log_scales(HookedAllocator<float>(hooks)),
        rotations(HookedAllocator<float>(hooks)),
        opacity_logits(HookedAllocator<float>(hooks)),
        sh(HookedAllocator<float>(hooks)) {}

  int sh_degree = 0;
  Buffer<float> positions;       // 3 per Gaussian
  Buffer<float> log_scales;      // 3 per Gaussian
  Buffer<float> rotations;       // 4 per Gaussian: w, x, y, z
  Buffer<float> opacity_logits;  // 1 per Gaussian
  Buffer<float> sh;              // 3 * ShCoefficients(sh_degree) per Gaussian

  size_t size() const { return opacity_logits.size(); }
  int sh_floats() const { return 3 * ShCoefficients(sh_degree); }

  // Sets the count, keeping the first min(old, n) Gaussians.
  void Resize(size_t n) {
    positions.resize(3 * n);
    log_scales.resize(3 * n);
    rotations.resize(4 * n);
    opacity_logits.resize(n);
    sh.resize(static_cast<size_t>(sh_floats()) * n);
  }
};

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_GAUSSIAN_SET_H_
