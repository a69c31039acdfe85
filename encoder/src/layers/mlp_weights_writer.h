// Encoding of MLP_WEIGHTS (bitstream-spec 4.3): per-tensor uniform quantization to at most
// 12-bit integers, each tensor a symbol block.
#ifndef M4D_ENCODER_LAYERS_MLP_WEIGHTS_WRITER_H_
#define M4D_ENCODER_LAYERS_MLP_WEIGHTS_WRITER_H_

#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/mlp_weights.h"

namespace m4d {

// Writes the float weights (shapes as MlpShapes gives) quantized with `bits` (2..12) per
// value, step = max |w| / (2^(bits-1) - 1) per tensor.
Status WriteMlpWeights(const MlpWeights& weights, int bits, RansLayout layout, ByteWriter* out);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_MLP_WEIGHTS_WRITER_H_
