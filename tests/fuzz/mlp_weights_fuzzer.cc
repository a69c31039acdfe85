// libFuzzer target for MLP_WEIGHTS: the first two bytes pick the configuration (features,
// hidden layers and width, within the specification's limits), the rest is the payload.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/layers/mlp_weights.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  m4d::MlpConfig config;
  config.hidden_layers = 1 + (data[0] & 3);
  config.hidden_width = 1 + data[1] % 64;
  const int features = 1 + (data[0] >> 2) % 32;
  m4d::ByteReader reader(data + 2, size - 2);
  m4d::MlpWeights weights;
  if (m4d::ReadMlpWeights(&reader, m4d::RansLayout::kInterleaved, features, config, &weights)
          .ok() &&
      weights.layers.size() != static_cast<size_t>(config.hidden_layers) + 1) {
    std::abort();
  }
  return 0;
}
