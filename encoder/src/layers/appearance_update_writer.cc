#include "encoder/src/layers/appearance_update_writer.h"

#include <cmath>
#include <cstdlib>

#include "encoder/src/entropy/symbol_block_writer.h"

namespace m4d {

Status WriteAppearanceUpdate(float step, const std::vector<int32_t>& values, RansLayout layout,
                             ByteWriter* out) {
  if (!std::isfinite(step) || !(step > 0.0f)) {
    return Status(M4D_ERR_INVALID_ARG, "appearance: the step must be finite and positive");
  }
  for (int32_t v : values) {
    if (std::abs(v) > kMaxAppearanceValue) {
      return Status(M4D_ERR_INVALID_ARG, "appearance: a value outside +-2047");
    }
  }
  out->WriteF32(step);
  return WriteSymbolBlock(values.data(), values.size(), layout, out);
}

}  // namespace m4d
