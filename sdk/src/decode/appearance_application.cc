#include "sdk/src/decode/appearance_application.h"

#include <cstddef>

namespace m4d {

void ApplyAppearanceUpdate(const AppearanceUpdate& update, GaussianSet* set) {
  const size_t stride = static_cast<size_t>(set->sh_floats());
  const int32_t* q = update.values.data();
  float* dc = set->sh.data();  // coefficient 0 of each channel leads a Gaussian's SH
  for (size_t i = 0; i < set->size(); ++i, dc += stride, q += 3) {
    for (int c = 0; c < 3; ++c) {
      const float change = static_cast<float>(q[c]) * update.step;
      dc[c] = dc[c] + change;
    }
  }
}

}  // namespace m4d
