// libFuzzer target for MOTION_GRID: the first byte picks a small grid configuration (levels,
// channels, resolutions within the limits) and its top bit the syntax (bricks, or active voxels
// of a fixed set of Gaussians spread over the unit cube), the rest is the payload. A grid that
// decodes has every level at its configured size, and with active voxels zero elsewhere.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/layers/motion_grid.h"

namespace {

std::vector<float> SpreadPositions() {
  std::vector<float> p;
  for (int i = 0; i < 64; ++i) {
    p.push_back(static_cast<float>(i % 4) / 3.0f);
    p.push_back(static_cast<float>((i / 4) % 4) / 3.0f);
    p.push_back(static_cast<float>(i / 16) / 3.0f + 0.01f * static_cast<float>(i % 3));
  }
  return p;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  m4d::GridConfig config;
  config.num_levels = 1 + (data[0] & 3);
  for (int l = 0; l < config.num_levels; ++l) {
    config.channels[l] = 1 + ((data[0] >> 2) + l) % 4;
    config.resolution[l] = 2 + ((data[0] >> 4) * 3 + 5 * l) % 30;
  }
  static const std::vector<float> positions = SpreadPositions();
  const bool active = (data[0] & 0x80) != 0;
  m4d::ByteReader reader(data + 1, size - 1);
  m4d::MotionGrid grid;
  const m4d::Status status =
      active ? m4d::ReadActiveMotionGrid(&reader, m4d::RansLayout::kInterleaved, config,
                                         positions.data(), positions.size() / 3, &grid)
             : m4d::ReadMotionGrid(&reader, m4d::RansLayout::kInterleaved, config, &grid);
  if (status.ok()) {
    for (int l = 0; l < config.num_levels; ++l) {
      if (grid.values[l].size() != config.level_values(l)) std::abort();
    }
  }
  return 0;
}
