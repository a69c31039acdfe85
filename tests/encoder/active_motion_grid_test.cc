// MOTION_GRID's active-voxel syntax (bitstream 0.10, spec 4.4): only the voxels the dynamic set
// reads are coded, and dropping the rest changes no moved Gaussian.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "encoder/src/layers/motion_grid_writer.h"
#include "encoder/src/motion/motion_stencil.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/decode/motion_application.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {
namespace {

GridConfig SmallConfig() {
  GridConfig config;
  config.num_levels = 2;
  config.channels[0] = 3;
  config.channels[1] = 2;
  config.resolution[0] = 9;
  config.resolution[1] = 20;
  return config;
}

// A grid over the box [-1, 1]^3 with random values at every voxel.
FloatMotionGrid DenseRandomGrid(const GridConfig& config, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-0.5f, 0.5f);
  FloatMotionGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.box_min[a] = -1.0f;
    grid.box_scale[a] = 0.5f;
  }
  for (int l = 0; l < config.num_levels; ++l) {
    grid.step[l] = 1.0f / 32;
    grid.values[l].resize(config.level_values(l));
    for (float& v : grid.values[l]) v = value(rng);
  }
  return grid;
}

// Gaussians around `center`, some outside the box.
GaussianSet Gaussians(size_t n, uint64_t seed, float center_x) {
  const float center[3] = {center_x, 0.1f, -0.2f};
  return SyntheticGaussianSet(n, 0, seed, center, 0.9f);
}

std::vector<uint8_t> Write(const GridConfig& config, const FloatMotionGrid& grid,
                           const GaussianSet& set, bool active) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  const Status status = active
                            ? WriteActiveMotionGrid(config, grid, set.positions.data(), set.size(),
                                                    RansLayout::kInterleaved, &writer)
                            : WriteMotionGrid(config, grid, RansLayout::kInterleaved, &writer);
  EXPECT_TRUE(status.ok()) << status.message();
  return payload;
}

Status Read(const std::vector<uint8_t>& payload, const GridConfig& config, const GaussianSet& set,
            bool active, MotionGrid* grid) {
  ByteReader reader(payload.data(), payload.size());
  const Status status = active ? ReadActiveMotionGrid(&reader, RansLayout::kInterleaved, config,
                                                      set.positions.data(), set.size(), grid)
                               : ReadMotionGrid(&reader, RansLayout::kInterleaved, config, grid);
  if (status.ok() && reader.remaining() != 0) return Status(M4D_ERR_BITSTREAM, "bytes left");
  return status;
}

int32_t Quantize(float v, float step) {
  return static_cast<int32_t>(std::fmin(std::fmax(std::floor(v / step + 0.5f), -2047), 2047));
}

// The decoder's grid holds the quantized value at every voxel the encoder's stencil (its own
// account of spec 6.3 steps 1-2) reads, and zero at every other voxel; the payload is far
// smaller than the brick syntax's.
TEST(ActiveMotionGridTest, CodesTheVoxelsTheSetReadsAndNothingElse) {
  const GridConfig config = SmallConfig();
  const FloatMotionGrid in = DenseRandomGrid(config, 1);
  const GaussianSet set = Gaussians(40, 2, 0.3f);
  MotionStencil stencil;
  GridBox box;
  for (int a = 0; a < 3; ++a) {
    box.min[a] = in.box_min[a];
    box.scale[a] = in.box_scale[a];
  }
  BuildMotionStencil(config, box, set.positions.data(), set.size(), &stencil);
  const std::vector<uint8_t> payload = Write(config, in, set, true);
  MotionGrid out;
  ASSERT_TRUE(Read(payload, config, set, true, &out).ok());
  size_t outside = 0;
  for (uint8_t inside : stencil.inside) outside += inside ? 0 : 1;
  EXPECT_GT(outside, 0u);  // the box test of step 1 is exercised
  for (int l = 0; l < config.num_levels; ++l) {
    const std::set<uint32_t> active(stencil.active[l].begin(), stencil.active[l].end());
    ASSERT_FALSE(active.empty());
    const int c = config.channels[l];
    for (size_t i = 0; i < out.values[l].size(); ++i) {
      const bool read = active.count(static_cast<uint32_t>(i / c)) > 0;
      ASSERT_EQ(out.values[l][i], read ? Quantize(in.values[l][i], in.step[l]) : 0)
          << l << " " << i;
    }
  }
  EXPECT_LT(payload.size(), Write(config, in, set, false).size() / 2);
}

// Dropping the inactive voxels moves every Gaussian exactly as the brick syntax's full grid.
TEST(ActiveMotionGridTest, MovesTheSetAsTheFullGrid) {
  const GridConfig config = SmallConfig();
  const FloatMotionGrid in = DenseRandomGrid(config, 3);
  const GaussianSet set = Gaussians(60, 4, 0.0f);
  const MlpWeights mlp = SyntheticMlp(config.feature_count(), MlpConfig(), 5);
  MotionGrid full, active;
  ASSERT_TRUE(Read(Write(config, in, set, false), config, set, false, &full).ok());
  ASSERT_TRUE(Read(Write(config, in, set, true), config, set, true, &active).ok());
  GaussianSet by_full = set, by_active = set;
  ApplyMotion(config, full, mlp, &by_full);
  ApplyMotion(config, active, mlp, &by_active);
  EXPECT_EQ(by_full.positions, by_active.positions);
  EXPECT_EQ(by_full.rotations, by_active.rotations);
  EXPECT_NE(by_full.positions, set.positions);
}

// One MotionGrid read frame after frame, as the decoder does, with the set moving, leaving the
// box, and the brick syntax in between, equals a fresh read each time; a truncated payload
// fails at every length.
TEST(ActiveMotionGridTest, ReusedGridEqualsFreshReadAndTruncationFails) {
  const GridConfig config = SmallConfig();
  MotionGrid reused;
  for (int frame = 0; frame < 5; ++frame) {
    const FloatMotionGrid in = DenseRandomGrid(config, 10 + frame);
    // Frame 2 lies outside the box (an empty grid); frame 3 is read with the brick syntax.
    const GaussianSet set = Gaussians(30, 20 + frame, frame == 2 ? 9.0f : 0.4f * frame - 0.6f);
    const bool active = frame != 3;
    const std::vector<uint8_t> payload = Write(config, in, set, active);
    MotionGrid fresh;
    ASSERT_TRUE(Read(payload, config, set, active, &fresh).ok());
    ASSERT_TRUE(Read(payload, config, set, active, &reused).ok());
    for (int l = 0; l < config.num_levels; ++l) {
      ASSERT_EQ(reused.values[l], fresh.values[l]) << "frame " << frame << " level " << l;
    }
    if (!active) continue;
    for (size_t size = 0; size < payload.size(); ++size) {
      const std::vector<uint8_t> cut(payload.begin(), payload.begin() + size);
      ASSERT_EQ(Read(cut, config, set, true, &reused).code(), M4D_ERR_BITSTREAM) << size;
    }
    ASSERT_TRUE(Read(payload, config, set, true, &reused).ok());
  }
}

}  // namespace
}  // namespace m4d
