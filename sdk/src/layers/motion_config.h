// Configuration of the motion grid and the shared MLP, carried by the sequence header
// (bitstream-spec 4.1).
#ifndef M4D_SDK_LAYERS_MOTION_CONFIG_H_
#define M4D_SDK_LAYERS_MOTION_CONFIG_H_

#include <cstdint>

#include "sdk/src/common/spec_limits.h"

namespace m4d {

struct GridConfig {
  int num_levels = 3;
  int channels[kMaxGridLevels] = {4, 4, 2, 0};
  int resolution[kMaxGridLevels] = {32, 64, 128, 0};

  int feature_count() const {
    int f = 0;
    for (int l = 0; l < num_levels; ++l) f += channels[l];
    return f;
  }
  uint64_t level_values(int l) const {
    uint64_t r = static_cast<uint64_t>(resolution[l]);
    return r * r * r * static_cast<uint64_t>(channels[l]);
  }
  uint64_t total_values() const {
    uint64_t t = 0;
    for (int l = 0; l < num_levels; ++l) t += level_values(l);
    return t;
  }
};

struct MlpConfig {
  int hidden_layers = 1;
  int hidden_width = 64;
};

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_MOTION_CONFIG_H_
