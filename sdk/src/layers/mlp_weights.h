// MlpWeights: the shared MLP of a GOP (bitstream-spec 4.3), and its reader.
#ifndef M4D_SDK_LAYERS_MLP_WEIGHTS_H_
#define M4D_SDK_LAYERS_MLP_WEIGHTS_H_

#include <vector>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

struct MlpLayer {
  int inputs = 0;
  int outputs = 0;
  std::vector<float> weights;  // [outputs][inputs], row-major by output
  std::vector<float> biases;   // [outputs]
};

struct MlpWeights {
  std::vector<MlpLayer> layers;  // hidden_layers + 1 linear layers
};

// Shapes of the H + 1 layers for `feature_count` inputs (spec 4.1).
std::vector<MlpLayer> MlpShapes(int feature_count, const MlpConfig& config);

// Reads an MLP_WEIGHTS payload.
Status ReadMlpWeights(ByteReader* reader, RansLayout layout, int feature_count,
                      const MlpConfig& config, MlpWeights* out);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_MLP_WEIGHTS_H_
