#include "sdk/src/layers/appearance_update.h"

#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {

Status ReadAppearanceUpdate(ByteReader* reader, RansLayout layout, uint32_t count,
                            AppearanceUpdate* update) {
  if (!reader->ReadFiniteF32(&update->step) || !(update->step > 0.0f)) {
    return BitstreamError("bad or missing step");
  }
  // count is the dynamic set's size, which MAX_GAUSSIANS_PER_SET bounds.
  const uint32_t values = 3 * count;
  update->values.resize(values);
  return ReadSymbolBlock(reader, layout, values, -32768, 32767, update->values.data());
}

}  // namespace m4d
