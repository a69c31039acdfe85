// Writes an APPEARANCE payload (bitstream-spec 4.7): the step, then the values as one symbol
// block.
#ifndef M4D_ENCODER_LAYERS_APPEARANCE_UPDATE_WRITER_H_
#define M4D_ENCODER_LAYERS_APPEARANCE_UPDATE_WRITER_H_

#include <cstdint>
#include <vector>

#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {

// values: 3 per Gaussian of the moved dynamic set (r, g, b), each within +-kMaxAppearanceValue.
Status WriteAppearanceUpdate(float step, const std::vector<int32_t>& values, RansLayout layout,
                             ByteWriter* out);

// What the symbol block's alphabet limit leaves to one value.
constexpr int32_t kMaxAppearanceValue = 2047;

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_APPEARANCE_UPDATE_WRITER_H_
