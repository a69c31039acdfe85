#include "encoder/src/pipeline/coded_motion.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "encoder/src/layers/mlp_weights_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"

namespace m4d {

Status DecodedMlp(const MlpWeights& mlp, const EncoderOptions& o, MlpWeights* decoded) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  M4D_RETURN_IF_ERROR(WriteMlpWeights(mlp, o.mlp_bits, RansLayout::kInterleaved, &writer));
  ByteReader reader(payload.data(), payload.size());
  return ReadMlpWeights(&reader, RansLayout::kInterleaved, o.grid.feature_count(), o.mlp, decoded);
}

void DenseGrids(const GridConfig& config, const float* steps, const MotionEstimationResult* motion,
                const GridBox& box, FloatMotionGrid* coded, MotionGrid* decoded) {
  for (int a = 0; a < 3; ++a) {
    coded->box_min[a] = decoded->box_min[a] = box.min[a];
    coded->box_scale[a] = decoded->box_scale[a] = box.scale[a];
  }
  for (int l = 0; l < kMaxGridLevels; ++l) {
    coded->step[l] = decoded->step[l] = steps[l];
    const size_t size = l < config.num_levels ? config.level_values(l) : 0;
    coded->values[l].assign(size, 0.0f);
    decoded->values[l].assign(size, 0);
    decoded->nonzero_bricks[l].clear();
    if (!motion || l >= config.num_levels) continue;
    const int channels = config.channels[l];
    const std::vector<uint32_t>& active = motion->stencil.active[l];
    const std::vector<float>& values = motion->parameters.grid[l];
    for (size_t v = 0; v < active.size(); ++v) {
      for (int c = 0; c < channels; ++c) {
        const float q = values[v * channels + c];
        const size_t index = static_cast<size_t>(active[v]) * channels + c;
        coded->values[l][index] = q * steps[l];
        decoded->values[l][index] = static_cast<int16_t>(q);
      }
    }
  }
}

void SkipMotion(FloatMotionGrid* grid) {
  for (int a = 0; a < 3; ++a) {
    grid->box_min[a] = std::numeric_limits<float>::max();
    grid->box_scale[a] = 1.0f;
  }
  for (std::vector<float>& level : grid->values) std::fill(level.begin(), level.end(), 0.0f);
}

}  // namespace m4d
