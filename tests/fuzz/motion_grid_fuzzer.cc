// libFuzzer target for MOTION_GRID: the first byte picks a small grid configuration (levels,
// channels, resolutions within the limits), the rest is the payload. A grid that decodes has
// every level at its configured size.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/layers/motion_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  m4d::GridConfig config;
  config.num_levels = 1 + (data[0] & 3);
  for (int l = 0; l < config.num_levels; ++l) {
    config.channels[l] = 1 + ((data[0] >> 2) + l) % 4;
    config.resolution[l] = 2 + ((data[0] >> 4) * 3 + 5 * l) % 30;
  }
  m4d::ByteReader reader(data + 1, size - 1);
  m4d::MotionGrid grid;
  if (m4d::ReadMotionGrid(&reader, m4d::RansLayout::kInterleaved, config, &grid).ok()) {
    for (int l = 0; l < config.num_levels; ++l) {
      if (grid.values[l].size() != config.level_values(l)) std::abort();
    }
  }
  return 0;
}
