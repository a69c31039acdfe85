#include "encoder/src/layers/mlp_weights_writer.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "sdk/src/common/spec_limits.h"

namespace m4d {
namespace {

Status InvalidArg(const std::string& message) {
  return Status(M4D_ERR_INVALID_ARG, "MLP weights: " + message);
}

// Symmetric uniform quantization of one tensor: step = max |w| / max_q, q = floor(w/step+0.5).
struct QuantizedTensor {
  float step = 1.0f;
  std::vector<int32_t> q;
};

Status Quantize(const std::vector<float>& values, int max_q, QuantizedTensor* out) {
  float max_abs = 0.0f;
  for (float v : values) {
    if (!std::isfinite(v)) return InvalidArg("value not finite");
    max_abs = std::max(max_abs, std::fabs(v));
  }
  const float step = max_abs / static_cast<float>(max_q);
  // An all-zero (or all-subnormal) tensor codes as zeros with a nominal step.
  out->step = step >= FLT_MIN ? step : 1.0f;
  out->q.resize(values.size());
  const float limit = static_cast<float>(max_q);
  for (size_t i = 0; i < values.size(); ++i) {
    const float q = std::floor(values[i] / out->step + 0.5f);
    out->q[i] = static_cast<int32_t>(std::min(std::max(q, -limit), limit));
  }
  return Status::Ok();
}

}  // namespace

Status WriteMlpWeights(const MlpWeights& weights, int bits, RansLayout layout, ByteWriter* out) {
  if (bits < 2 || bits > 12) return InvalidArg("bits " + std::to_string(bits) + " not in 2..12");
  if (weights.layers.size() < 2 || weights.layers.size() > kMaxMlpHiddenLayers + 1) {
    return InvalidArg("layer count out of range 2..5");
  }
  const int max_q = (1 << (bits - 1)) - 1;
  std::vector<QuantizedTensor> tensors(2 * weights.layers.size());
  for (size_t j = 0; j < weights.layers.size(); ++j) {
    const MlpLayer& layer = weights.layers[j];
    const std::string name = "layer " + std::to_string(j);
    if (layer.inputs < 1 || layer.outputs < 1 ||
        layer.weights.size() != static_cast<size_t>(layer.inputs) * layer.outputs ||
        layer.biases.size() != static_cast<size_t>(layer.outputs)) {
      return InvalidArg(name + ": shape and array sizes disagree");
    }
    if (j > 0 && layer.inputs != weights.layers[j - 1].outputs) {
      return InvalidArg(name + ": inputs differ from the previous layer's outputs");
    }
    M4D_RETURN_IF_ERROR(Quantize(layer.weights, max_q, &tensors[2 * j]));
    M4D_RETURN_IF_ERROR(Quantize(layer.biases, max_q, &tensors[2 * j + 1]));
  }
  if (weights.layers.back().outputs != kMlpOutputs) return InvalidArg("last layer needs 7 outputs");
  for (const QuantizedTensor& t : tensors) {
    out->WriteF32(t.step);
    M4D_RETURN_IF_ERROR(WriteSymbolBlock(t.q.data(), t.q.size(), layout, out));
  }
  return Status::Ok();
}

}  // namespace m4d
