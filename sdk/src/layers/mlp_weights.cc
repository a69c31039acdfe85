#include "sdk/src/layers/mlp_weights.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "sdk/src/common/spec_limits.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {
namespace {

// Reads a step and a symbol block of `count` values and dequantizes them (spec 4.3).
Status ReadTensor(ByteReader* reader, RansLayout layout, const std::string& what,
                  std::vector<int32_t>* scratch, std::vector<float>* out) {
  float step;
  if (!reader->ReadFiniteF32(&step)) return BitstreamError(what + ": bad or missing step");
  scratch->resize(out->size());
  Status status = ReadSymbolBlock(reader, layout, static_cast<uint32_t>(out->size()),
                                  -kMaxSymbolMagnitude, kMaxSymbolMagnitude, scratch->data());
  if (!status.ok()) return Status(status.code(), what + ": " + status.message());
  for (size_t i = 0; i < out->size(); ++i) (*out)[i] = static_cast<float>((*scratch)[i]) * step;
  return Status::Ok();
}

}  // namespace

std::vector<MlpLayer> MlpShapes(int feature_count, const MlpConfig& config) {
  std::vector<MlpLayer> layers(config.hidden_layers + 1);
  for (int j = 0; j <= config.hidden_layers; ++j) {
    MlpLayer& layer = layers[j];
    layer.inputs = j == 0 ? feature_count : config.hidden_width;
    layer.outputs = j == config.hidden_layers ? kMlpOutputs : config.hidden_width;
    layer.weights.assign(static_cast<size_t>(layer.inputs) * layer.outputs, 0.0f);
    layer.biases.assign(layer.outputs, 0.0f);
  }
  return layers;
}

Status ReadMlpWeights(ByteReader* reader, RansLayout layout, int feature_count,
                      const MlpConfig& config, MlpWeights* out) {
  std::vector<MlpLayer> layers = MlpShapes(feature_count, config);
  std::vector<int32_t> scratch;
  for (size_t j = 0; j < layers.size(); ++j) {
    const std::string layer = "layer " + std::to_string(j);
    M4D_RETURN_IF_ERROR(
        ReadTensor(reader, layout, layer + " weights", &scratch, &layers[j].weights));
    M4D_RETURN_IF_ERROR(ReadTensor(reader, layout, layer + " biases", &scratch, &layers[j].biases));
  }
  out->layers = std::move(layers);
  return Status::Ok();
}

}  // namespace m4d
