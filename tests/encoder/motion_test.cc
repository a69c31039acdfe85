// Motion grid and MLP layers (spec 4.3, 4.4) and the normative motion application (6.3).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "encoder/src/layers/mlp_weights_writer.h"
#include "encoder/src/layers/motion_grid_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/decode/motion_application.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_config.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

GridConfig MakeConfig(std::vector<int> channels, std::vector<int> resolution) {
  GridConfig config;
  config.num_levels = static_cast<int>(channels.size());
  for (int l = 0; l < kMaxGridLevels; ++l) {
    config.channels[l] = l < config.num_levels ? channels[l] : 0;
    config.resolution[l] = l < config.num_levels ? resolution[l] : 0;
  }
  return config;
}

Status ReadGrid(const std::vector<uint8_t>& payload, const GridConfig& config, MotionGrid* grid,
                size_t* remaining = nullptr) {
  ByteReader reader(payload.data(), payload.size());
  Status status = ReadMotionGrid(&reader, RansLayout::kInterleaved, config, grid);
  if (remaining) *remaining = reader.remaining();
  return status;
}

int32_t Quantize(float v, float step) {
  return static_cast<int32_t>(std::min(std::max(std::floor(v / step + 0.5f), -2047.0f), 2047.0f));
}

// A float grid whose content is non-zero only in the bricks `keep` accepts.
template <typename Keep>
FloatMotionGrid SparseFloatGrid(const GridConfig& config, std::mt19937* rng, Keep keep) {
  FloatMotionGrid grid;
  grid.box_min[0] = -1.5f;
  grid.box_scale[2] = 0.25f;
  std::uniform_real_distribution<float> value(-40.0f, 40.0f);
  for (int l = 0; l < config.num_levels; ++l) {
    const int r = config.resolution[l], c = config.channels[l];
    grid.step[l] = l == 1 ? 0.5f : 1.0f / 64;
    grid.values[l].assign(config.level_values(l), 0.0f);
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          if (!keep(l, z / kBrickSize, y / kBrickSize, x / kBrickSize)) continue;
          for (int ch = 0; ch < c; ++ch) {
            grid.values[l][((static_cast<size_t>(z) * r + y) * r + x) * c + ch] = value(*rng);
          }
        }
      }
    }
  }
  return grid;
}

// ---------------------------------------------------------------------------------------------
// Motion grid layer.

TEST(MotionGridTest, RoundTripPartialBricks) {
  std::mt19937 rng(1);
  const GridConfig configs[] = {MakeConfig({1}, {2}), MakeConfig({3}, {9}),
                                MakeConfig({2, 8}, {20, 9}),
                                MakeConfig({4, 1, 2, 5}, {2, 17, 20, 8})};
  for (const GridConfig& config : configs) {
    // Every brick whose coordinates sum to an even number carries content.
    FloatMotionGrid in = SparseFloatGrid(
        config, &rng, [](int, int bz, int by, int bx) { return (bz + by + bx) % 2 == 0; });
    // Exact halves, rounding up, and values beyond the clamp.
    in.values[0][0] = 0.5f * in.step[0];
    in.values[0].back() = -0.5f * in.step[0];
    if (in.values[0].size() > 2) in.values[0][1] = 1e6f;
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    ASSERT_TRUE(WriteMotionGrid(config, in, RansLayout::kInterleaved, &writer).ok());

    MotionGrid out;
    for (auto& v : out.values) v.assign(100, 7);  // stale content must be overwritten
    size_t remaining = 1;
    ASSERT_TRUE(ReadGrid(payload, config, &out, &remaining).ok());
    EXPECT_EQ(remaining, 0u);
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(out.box_min[a], in.box_min[a]);
      EXPECT_EQ(out.box_scale[a], in.box_scale[a]);
    }
    for (int l = 0; l < config.num_levels; ++l) {
      EXPECT_EQ(out.step[l], in.step[l]);
      ASSERT_EQ(out.values[l].size(), config.level_values(l));
      for (size_t i = 0; i < in.values[l].size(); ++i) {
        ASSERT_EQ(out.values[l][i], Quantize(in.values[l][i], in.step[l])) << "level " << l;
      }
    }
    EXPECT_EQ(out.values[0][0], 1);
    EXPECT_EQ(out.values[0].back(), 0);
    if (in.values[0].size() > 2) {
      EXPECT_EQ(out.values[0][1], 2047);
    }
    for (int l = config.num_levels; l < kMaxGridLevels; ++l) EXPECT_TRUE(out.values[l].empty());
  }
}

// A decoder reads every frame's grid into the same MotionGrid and zeroes only the bricks that
// were coded the frame before: the result must equal a fresh read, frame after frame.
TEST(MotionGridTest, ReusedGridEqualsFreshRead) {
  const GridConfig config = MakeConfig({2, 3}, {20, 33});
  std::mt19937 rng(5);
  MotionGrid reused;
  for (int frame = 0; frame < 6; ++frame) {
    // Content moves between bricks; frame 3 is all zero, frame 4 has every brick.
    const FloatMotionGrid in =
        SparseFloatGrid(config, &rng, [frame](int l, int bz, int by, int bx) {
          return frame == 4 || (frame != 3 && (bz * 7 + by * 3 + bx + l + frame) % 5 == 0);
        });
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    ASSERT_TRUE(WriteMotionGrid(config, in, RansLayout::kInterleaved, &writer).ok());
    MotionGrid fresh;
    ASSERT_TRUE(ReadGrid(payload, config, &fresh).ok());
    ASSERT_TRUE(ReadGrid(payload, config, &reused).ok());
    for (int l = 0; l < config.num_levels; ++l) {
      ASSERT_EQ(reused.values[l], fresh.values[l]) << "frame " << frame << " level " << l;
      for (size_t i = 0; i < in.values[l].size(); ++i) {
        ASSERT_EQ(fresh.values[l][i], Quantize(in.values[l][i], in.step[l]));
      }
    }
    // A truncated payload fails and must not leave the reused grid inconsistent.
    std::vector<uint8_t> cut(payload.begin(), payload.begin() + payload.size() / 2);
    EXPECT_FALSE(ReadGrid(cut, config, &reused).ok());
    ASSERT_TRUE(ReadGrid(payload, config, &reused).ok());
    for (int l = 0; l < config.num_levels; ++l) ASSERT_EQ(reused.values[l], fresh.values[l]);
  }
}

TEST(MotionGridTest, OnlyBricksWithContentAreFlagged) {
  const GridConfig config = MakeConfig({2}, {20});  // 3 bricks per axis, the last 4 wide
  std::mt19937 rng(2);
  auto keep = [](int, int bz, int by, int bx) { return bz == 2 && by == 0 && bx == 2; };
  const FloatMotionGrid in = SparseFloatGrid(config, &rng, keep);
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  ASSERT_TRUE(WriteMotionGrid(config, in, RansLayout::kInterleaved, &writer).ok());

  // Parse the syntax by hand: 6 box floats, the step, the flags, then the values.
  ByteReader reader(payload.data(), payload.size());
  float f;
  for (int i = 0; i < 7; ++i) ASSERT_TRUE(reader.ReadFiniteF32(&f));
  std::vector<int32_t> flags(27);
  ASSERT_TRUE(ReadSymbolBlock(&reader, RansLayout::kInterleaved, 27, 0, 1, flags.data()).ok());
  for (int b = 0; b < 27; ++b) EXPECT_EQ(flags[b], b == (2 * 3 + 0) * 3 + 2 ? 1 : 0) << b;
  std::vector<int32_t> values(4 * 8 * 4 * 2);  // partial brick: 4 x 8 x 4 voxels, 2 channels
  ASSERT_TRUE(ReadSymbolBlock(&reader, RansLayout::kInterleaved,
                              static_cast<uint32_t>(values.size()), -32768, 32767, values.data())
                  .ok());
  EXPECT_EQ(reader.remaining(), 0u);
  // Voxels of the brick in raster order, channels innermost.
  size_t i = 0;
  for (int z = 16; z < 20; ++z) {
    for (int y = 0; y < 8; ++y) {
      for (int x = 16; x < 20; ++x) {
        for (int c = 0; c < 2; ++c, ++i) {
          EXPECT_EQ(values[i], Quantize(in.values[0][((z * 20 + y) * 20 + x) * 2 + c], in.step[0]));
        }
      }
    }
  }
}

TEST(MotionGridTest, AllZeroGrid) {
  const GridConfig config = MakeConfig({4, 4, 2}, {32, 64, 128});
  FloatMotionGrid in;
  for (int l = 0; l < 3; ++l) in.values[l].assign(config.level_values(l), 0.001f);  // rounds to 0
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  ASSERT_TRUE(WriteMotionGrid(config, in, RansLayout::kInterleaved, &writer).ok());
  EXPECT_LT(payload.size(), 64u);
  MotionGrid out;
  ASSERT_TRUE(ReadGrid(payload, config, &out).ok());
  for (int l = 0; l < 3; ++l) {
    ASSERT_EQ(out.values[l].size(), config.level_values(l));
    EXPECT_TRUE(
        std::all_of(out.values[l].begin(), out.values[l].end(), [](int16_t v) { return v == 0; }));
  }
}

TEST(MotionGridTest, WriterRejectsBadInput) {
  const GridConfig config = MakeConfig({2, 1}, {9, 4});
  std::mt19937 rng(3);
  const FloatMotionGrid good =
      SparseFloatGrid(config, &rng, [](int, int, int, int) { return true; });
  auto fails = [&](const FloatMotionGrid& grid) {
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    Status status = WriteMotionGrid(config, grid, RansLayout::kInterleaved, &writer);
    return status.code() == M4D_ERR_INVALID_ARG && payload.empty();
  };
  EXPECT_FALSE(fails(good));
  const auto with = [&](auto change) {
    FloatMotionGrid grid = good;
    change(&grid);
    return grid;
  };
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->values[1].pop_back(); })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->values[0].push_back(0); })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->step[0] = 0; })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->step[1] = -1; })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->step[1] = kNaN; })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->box_scale[1] = 0; })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->box_scale[2] = kInf; })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->box_min[0] = kNaN; })));
  EXPECT_TRUE(fails(with([](FloatMotionGrid* g) { g->values[1][3] = kNaN; })));
}

// A payload with the given box_scale and one level (R = 2, C = 1) of the given flags and values.
std::vector<uint8_t> HandMadeGrid(float box_scale, float step, std::vector<int32_t> flags,
                                  std::vector<int32_t> values) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  for (int a = 0; a < 3; ++a) writer.WriteF32(0.0f);
  for (int a = 0; a < 3; ++a) writer.WriteF32(a == 1 ? box_scale : 1.0f);
  writer.WriteF32(step);
  EXPECT_TRUE(WriteSymbolBlock(flags.data(), flags.size(), RansLayout::kInterleaved, &writer).ok());
  EXPECT_TRUE(
      WriteSymbolBlock(values.data(), values.size(), RansLayout::kInterleaved, &writer).ok());
  return payload;
}

TEST(MotionGridTest, MalformedPayloads) {
  const GridConfig config = MakeConfig({1}, {2});
  MotionGrid grid;
  // The int16 extremes (one block's alphabet spans at most 4096 values).
  const std::vector<int32_t> top = {32767, 30000, 32767, 31000, 32000, 32766, 32767, 29000};
  const std::vector<int32_t> bottom = {-32768, -30000, -32767, -31000,
                                       -32000, -29000, -30500, -28700};
  ASSERT_TRUE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {1}, top), config, &grid).ok());
  EXPECT_EQ(std::vector<int16_t>(grid.values[0].begin(), grid.values[0].end()),
            std::vector<int16_t>(top.begin(), top.end()));
  ASSERT_TRUE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {1}, bottom), config, &grid).ok());
  EXPECT_EQ(std::vector<int16_t>(grid.values[0].begin(), grid.values[0].end()),
            std::vector<int16_t>(bottom.begin(), bottom.end()));
  ASSERT_TRUE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {0}, {}), config, &grid).ok());
  EXPECT_EQ(grid.values[0][0], 0);

  const std::vector<int32_t> eight = {1, -2, 3, -4, 5, -6, 7, -8};
  EXPECT_FALSE(ReadGrid(HandMadeGrid(0.0f, 0.5f, {1}, eight), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(-2.0f, 0.5f, {1}, eight), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(kInf, 0.5f, {1}, eight), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(kNaN, 0.5f, {1}, eight), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(1.0f, kInf, {1}, eight), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {2}, eight), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {-1}, eight), config, &grid).ok());
  std::vector<int32_t> high = top, low = bottom;
  high[3] = 32768;
  low[0] = -32769;
  EXPECT_FALSE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {1}, high), config, &grid).ok());
  EXPECT_FALSE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {1}, low), config, &grid).ok());
  // V_l follows from the flags: a block of the wrong length does not parse.
  EXPECT_FALSE(ReadGrid(HandMadeGrid(1.0f, 0.5f, {1}, {1, 2, 3, 4, 5, 6, 7}), config, &grid).ok());

  // Trailing data is left for the caller to reject.
  std::vector<uint8_t> payload = HandMadeGrid(1.0f, 0.5f, {1}, eight);
  payload.push_back(0);
  size_t remaining = 0;
  EXPECT_TRUE(ReadGrid(payload, config, &grid, &remaining).ok());
  EXPECT_EQ(remaining, 1u);
}

TEST(MotionGridTest, TruncationAtEveryByte) {
  const GridConfig config = MakeConfig({2, 3}, {9, 2});
  std::mt19937 rng(4);
  const FloatMotionGrid in =
      SparseFloatGrid(config, &rng, [](int l, int bz, int, int bx) { return l == 1 || bz != bx; });
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  ASSERT_TRUE(WriteMotionGrid(config, in, RansLayout::kInterleaved, &writer).ok());
  MotionGrid grid;
  ASSERT_TRUE(ReadGrid(payload, config, &grid).ok());
  for (size_t size = 0; size < payload.size(); ++size) {
    std::vector<uint8_t> cut(payload.begin(), payload.begin() + size);
    EXPECT_EQ(ReadGrid(cut, config, &grid).code(), M4D_ERR_BITSTREAM) << size;
  }
}

TEST(MotionGridTest, CorruptedBytesNeverCrash) {
  const GridConfig config = MakeConfig({2, 3}, {9, 2});
  std::mt19937 rng(8);
  const FloatMotionGrid in =
      SparseFloatGrid(config, &rng, [](int l, int bz, int, int bx) { return l == 1 || bz != bx; });
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  ASSERT_TRUE(WriteMotionGrid(config, in, RansLayout::kInterleaved, &writer).ok());
  std::uniform_int_distribution<size_t> position(0, payload.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255);
  MotionGrid grid;
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> bad = payload;
    for (int k = 0; k < 1 + i % 3; ++k) bad[position(rng)] = static_cast<uint8_t>(byte(rng));
    if (ReadGrid(bad, config, &grid).ok()) {
      for (int l = 0; l < 2; ++l) ASSERT_EQ(grid.values[l].size(), config.level_values(l));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// MLP layer.

MlpWeights RandomMlp(int features, const MlpConfig& config, std::mt19937* rng, float scale) {
  MlpWeights mlp;
  mlp.layers = MlpShapes(features, config);
  std::normal_distribution<float> normal(0.0f, scale);
  for (MlpLayer& layer : mlp.layers) {
    for (float& w : layer.weights) w = normal(*rng);
    for (float& b : layer.biases) b = normal(*rng);
  }
  return mlp;
}

TEST(MlpWeightsTest, Shapes) {
  const std::vector<MlpLayer> layers = MlpShapes(10, MlpConfig{3, 64});
  ASSERT_EQ(layers.size(), 4u);
  const int inputs[] = {10, 64, 64, 64}, outputs[] = {64, 64, 64, 7};
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(layers[j].inputs, inputs[j]);
    EXPECT_EQ(layers[j].outputs, outputs[j]);
    EXPECT_EQ(layers[j].weights.size(), static_cast<size_t>(inputs[j] * outputs[j]));
    EXPECT_EQ(layers[j].biases.size(), static_cast<size_t>(outputs[j]));
  }
}

TEST(MlpWeightsTest, RoundTrip) {
  std::mt19937 rng(5);
  for (int bits : {2, 8, 12}) {
    const MlpConfig config{2, 24};
    MlpWeights in = RandomMlp(10, config, &rng, 0.3f);
    for (float& w : in.layers[1].biases) w = 0;  // all-zero tensor
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    ASSERT_TRUE(WriteMlpWeights(in, bits, RansLayout::kInterleaved, &writer).ok());
    ByteReader reader(payload.data(), payload.size());
    MlpWeights out;
    ASSERT_TRUE(ReadMlpWeights(&reader, RansLayout::kInterleaved, 10, config, &out).ok());
    EXPECT_EQ(reader.remaining(), 0u);
    ASSERT_EQ(out.layers.size(), 3u);
    const float max_q = static_cast<float>((1 << (bits - 1)) - 1);
    for (size_t j = 0; j < 3; ++j) {
      for (int t = 0; t < 2; ++t) {
        const std::vector<float>& a = t ? in.layers[j].biases : in.layers[j].weights;
        const std::vector<float>& b = t ? out.layers[j].biases : out.layers[j].weights;
        ASSERT_EQ(a.size(), b.size());
        float max_abs = 0;
        for (float v : a) max_abs = std::max(max_abs, std::fabs(v));
        const float step = max_abs / max_q;
        for (size_t i = 0; i < a.size(); ++i) {
          if (max_abs == 0) {
            EXPECT_EQ(b[i], 0.0f);
            continue;
          }
          // Dequantized values are float(q) * step, within half a step.
          const float q = std::round(b[i] / step);
          EXPECT_EQ(q * step, b[i]);
          EXPECT_LE(std::fabs(q), max_q);
          EXPECT_LE(std::fabs(a[i] - b[i]), 0.5001f * step);
        }
      }
    }
  }
}

// An MLP_WEIGHTS payload with every tensor's integers and steps given.
std::vector<uint8_t> HandMadeMlp(const std::vector<MlpLayer>& shapes, float step, int32_t q) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  for (const MlpLayer& layer : shapes) {
    for (size_t count : {layer.weights.size(), layer.biases.size()}) {
      writer.WriteF32(step);
      const std::vector<int32_t> values(count, q);
      EXPECT_TRUE(WriteSymbolBlock(values.data(), count, RansLayout::kInterleaved, &writer).ok());
    }
  }
  return payload;
}

TEST(MlpWeightsTest, DequantizationAndErrors) {
  const MlpConfig config{1, 3};
  const std::vector<MlpLayer> shapes = MlpShapes(2, config);
  auto read = [&](const std::vector<uint8_t>& payload, MlpWeights* out) {
    ByteReader reader(payload.data(), payload.size());
    return ReadMlpWeights(&reader, RansLayout::kInterleaved, 2, config, out);
  };
  MlpWeights out;
  // The largest integer a symbol block can carry, with a step that overflows it to infinity.
  ASSERT_TRUE(read(HandMadeMlp(shapes, 0.25f, 1 << 23), &out).ok());
  EXPECT_EQ(out.layers[1].weights[20], 2097152.0f);
  ASSERT_TRUE(read(HandMadeMlp(shapes, -3e38f, -5), &out).ok());
  EXPECT_EQ(out.layers[0].biases[2], kInf);

  EXPECT_FALSE(read(HandMadeMlp(shapes, kNaN, 1), &out).ok());
  EXPECT_FALSE(read(HandMadeMlp(shapes, kInf, 1), &out).ok());
  const std::vector<uint8_t> good = HandMadeMlp(shapes, 0.5f, 3);
  for (size_t size = 0; size < good.size(); ++size) {
    EXPECT_FALSE(read(std::vector<uint8_t>(good.begin(), good.begin() + size), &out).ok());
  }
  // Values beyond 2^23 in magnitude cannot be coded (min_value limit of symbol_block).
  std::vector<uint8_t> big;
  ByteWriter writer(&big);
  writer.WriteF32(1.0f);
  writer.WriteVarUint(1);
  writer.WriteVarSint((1 << 23) + 1);
  EXPECT_FALSE(read(big, &out).ok());
}

TEST(MlpWeightsTest, WriterRejectsBadInput) {
  std::mt19937 rng(6);
  const MlpWeights good = RandomMlp(4, MlpConfig{1, 8}, &rng, 1.0f);
  auto fails = [](const MlpWeights& mlp, int bits) {
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    return WriteMlpWeights(mlp, bits, RansLayout::kInterleaved, &writer).code() ==
               M4D_ERR_INVALID_ARG &&
           payload.empty();
  };
  EXPECT_FALSE(fails(good, 12));
  EXPECT_TRUE(fails(good, 1));
  EXPECT_TRUE(fails(good, 13));
  MlpWeights bad = good;
  bad.layers[1].weights[5] = kInf;
  EXPECT_TRUE(fails(bad, 8));
  bad = good;
  bad.layers[0].biases.pop_back();
  EXPECT_TRUE(fails(bad, 8));
  bad = good;
  bad.layers[1].inputs = 4;
  bad.layers[1].weights.resize(4 * 7);
  EXPECT_TRUE(fails(bad, 8));
  bad = good;
  bad.layers.pop_back();
  EXPECT_TRUE(fails(bad, 8));
}

// ---------------------------------------------------------------------------------------------
// Motion application.

// Spec 6.3 as written, one Gaussian at a time. Like the SDK it must not be contracted into
// FMA, whatever flags the tests are built with (FMA is baseline on AArch64). GCC's vectoriser
// fuses into vfmaddsub despite the attribute, hence no vectorisation here.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off", "no-tree-vectorize")
#endif
void ReferenceApplyMotion(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                          GaussianSet* set) {
  for (size_t g = 0; g < set->size(); ++g) {
    float* p = &set->positions[3 * g];
    float* q = &set->rotations[4 * g];
    // 1. Box coordinates.
    float u[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      u[a] = (p[a] - grid.box_min[a]) * grid.box_scale[a];
      if (!(u[a] >= 0 && u[a] <= 1)) inside = false;
    }
    if (!inside) continue;
    // 2. Features.
    std::vector<float> x;
    for (int l = 0; l < config.num_levels; ++l) {
      const int r = config.resolution[l], channels = config.channels[l];
      int i[3];
      float w0[3], w1[3];
      for (int a = 0; a < 3; ++a) {
        const float ga = u[a] * static_cast<float>(r - 1);
        i[a] = std::min(static_cast<int>(std::trunc(ga)), r - 2);
        const float t = ga - static_cast<float>(i[a]);
        w0[a] = 1 - t;
        w1[a] = t;
      }
      for (int c = 0; c < channels; ++c) {
        float acc = 0;
        for (int k = 0; k < 8; ++k) {
          const int dx = k & 1, dy = (k >> 1) & 1, dz = (k >> 2) & 1;
          const float w = ((dx ? w1[0] : w0[0]) * (dy ? w1[1] : w0[1])) * (dz ? w1[2] : w0[2]);
          const size_t index =
              ((static_cast<size_t>(i[2] + dz) * r + (i[1] + dy)) * r + (i[0] + dx)) * channels + c;
          acc = acc + w * static_cast<float>(grid.values[l][index]);
        }
        x.push_back(acc * grid.step[l]);
      }
    }
    // 3. MLP.
    const size_t hidden = mlp.layers.size() - 1;
    for (size_t j = 0; j <= hidden; ++j) {
      const MlpLayer& layer = mlp.layers[j];
      std::vector<float> y(layer.outputs);
      for (int o = 0; o < layer.outputs; ++o) {
        float acc = layer.biases[o];
        for (int in = 0; in < layer.inputs; ++in) {
          acc = acc + layer.weights[o * layer.inputs + in] * x[in];
        }
        y[o] = j < hidden ? (acc > 0 ? acc : acc * 0.01f) : acc;
      }
      x = y;
    }
    // 4. Finiteness.
    bool finite = true;
    for (int k = 0; k < 7; ++k) finite = finite && std::isfinite(x[k]);
    if (!finite) continue;
    // 5. Translation.
    for (int a = 0; a < 3; ++a) p[a] = p[a] + x[a];
    // 6. Rotation.
    const float dw = 1 + x[3], dx = x[4], dy = x[5], dz = x[6];
    const float qw = q[0], qx = q[1], qy = q[2], qz = q[3];
    const float rw = ((dw * qw - dx * qx) - dy * qy) - dz * qz;
    const float rx = ((dw * qx + dx * qw) + dy * qz) - dz * qy;
    const float ry = ((dw * qy - dx * qz) + dy * qw) + dz * qx;
    const float rz = ((dw * qz + dx * qy) - dy * qx) + dz * qw;
    const float n2 = ((rw * rw + rx * rx) + ry * ry) + rz * rz;
    if (n2 > 1e-30f && std::isfinite(n2)) {
      const float n = std::sqrt(n2);
      q[0] = rw / n;
      q[1] = rx / n;
      q[2] = ry / n;
      q[3] = rz / n;
    } else {
      q[0] = 1;
      q[1] = q[2] = q[3] = 0;
    }
  }
}
#if !defined(__clang__) && defined(__GNUC__)
#pragma GCC pop_options
#endif

GaussianSet MakeSet(const std::vector<float>& positions, const std::vector<float>& rotations) {
  GaussianSet set;
  set.Resize(positions.size() / 3);
  set.positions.assign(positions.begin(), positions.end());
  set.rotations.assign(rotations.begin(), rotations.end());
  for (size_t i = 0; i < set.log_scales.size(); ++i) set.log_scales[i] = static_cast<float>(i);
  for (size_t i = 0; i < set.sh.size(); ++i) set.sh[i] = static_cast<float>(i);
  return set;
}

MotionGrid ZeroGrid(const GridConfig& config) {
  MotionGrid grid;
  for (int l = 0; l < config.num_levels; ++l) grid.values[l].assign(config.level_values(l), 0);
  for (int l = 0; l < config.num_levels; ++l) grid.step[l] = 1.0f / 64;
  return grid;
}

TEST(MotionApplicationTest, BiasOnlyTranslation) {
  const GridConfig config = MakeConfig({4, 4, 2}, {32, 64, 128});
  MotionGrid grid = ZeroGrid(config);
  grid.box_min[0] = -1;
  grid.box_min[1] = -2;
  grid.box_scale[2] = 0.5f;
  MlpWeights mlp;
  mlp.layers = MlpShapes(10, MlpConfig{1, 64});
  const float bias[7] = {0.5f, -0.25f, 1.0f, 0, 0, 0, 0};
  std::copy(bias, bias + 7, mlp.layers[1].biases.begin());
  // Box x in [-1, 0], y in [-2, -1], z in [0, 2]. Inside on a corner; inside on the far z
  // face; outside in y; outside in z.
  GaussianSet set = MakeSet({0, -1, 0, -0.5f, -1.5f, 2, 0, 0, 0, -1, -2, 2.5f},
                            {1, 0, 0, 0, 0, 0, 0, 2, 0, 3, 0, 0, 0, 0, 1, 0});
  const GaussianSet original = set;
  ApplyMotion(config, grid, mlp, &set);
  const std::vector<float> moved = {0.5f, -1.25f, 1, 0, -1.75f, 3, 0, 0, 0, -1, -2, 2.5f};
  const std::vector<float> turned = {1, 0, 0, 0, 0, 0, 0, 1, 0, 3, 0, 0, 0, 0, 1, 0};
  EXPECT_EQ(std::vector<float>(set.positions.begin(), set.positions.end()), moved);
  EXPECT_EQ(std::vector<float>(set.rotations.begin(), set.rotations.end()), turned);
  EXPECT_EQ(set.log_scales, original.log_scales);
  EXPECT_EQ(set.sh, original.sh);
}

TEST(MotionApplicationTest, ComposedRotations) {
  const GridConfig config = MakeConfig({1}, {2});
  const MotionGrid grid = ZeroGrid(config);
  MlpWeights mlp;
  mlp.layers = MlpShapes(1, MlpConfig{1, 1});
  auto rotate = [&](std::vector<float> delta, std::vector<float> q) {
    std::copy(delta.begin(), delta.end(), mlp.layers[1].biases.begin() + 3);
    GaussianSet set = MakeSet({0.5f, 0.5f, 0.5f}, q);
    ApplyMotion(config, grid, mlp, &set);
    return std::vector<float>(set.rotations.begin(), set.rotations.end());
  };
  // 180 degrees about z after 180 degrees about x is 180 degrees about y.
  EXPECT_EQ(rotate({-1, 0, 0, 1}, {0, 1, 0, 0}), std::vector<float>({0, 0, 1, 0}));
  // d = (1, 0, 0, 1) composed with q = (1, 1, 0, 0) gives (1, 1, 1, 1), normalised.
  EXPECT_EQ(rotate({0, 0, 0, 1}, {1, 1, 0, 0}), std::vector<float>({0.5f, 0.5f, 0.5f, 0.5f}));
  const float h = 1.0f / std::sqrt(2.0f);
  EXPECT_EQ(rotate({0, 0, 0, 1}, {1, 0, 0, 0}), std::vector<float>({h, 0, 0, h}));
  // Degenerate products fall back to the identity: zero, tiny and overflowing norms.
  const std::vector<float> identity = {1, 0, 0, 0};
  EXPECT_EQ(rotate({0, 0, 0, 0}, {0, 0, 0, 0}), identity);
  EXPECT_EQ(rotate({-1, 0, 0, 0}, {0.3f, 0.1f, 0, 0}), identity);
  EXPECT_EQ(rotate({0, 0, 0, 0}, {1e-16f, 0, 0, 0}), identity);
  EXPECT_EQ(rotate({0, 0, 0, 0}, {1e20f, 0, 0, 0}), identity);
}

TEST(MotionApplicationTest, TrilinearFeatures) {
  // One level, R = 2, C = 1; the MLP passes feature 0 through to o[0] (ReLU of a positive).
  const GridConfig config = MakeConfig({1}, {2});
  MotionGrid grid = ZeroGrid(config);
  grid.step[0] = 0.25f;
  for (int i = 0; i < 8; ++i) grid.values[0][i] = static_cast<int16_t>(8 * (i + 1));
  MlpWeights mlp;
  mlp.layers = MlpShapes(1, MlpConfig{1, 1});
  mlp.layers[0].weights[0] = 1;
  mlp.layers[1].weights[0] = 1;
  GaussianSet set = MakeSet({0.5f, 0.5f, 0.5f, 1, 0, 0, 0, 1, 1, 0.25f, 0, 0},
                            {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
  ApplyMotion(config, grid, mlp, &set);
  // Centre: the mean 36 times the step; corners: the corner's value (x fastest, then y, z).
  EXPECT_EQ(set.positions[0], 0.5f + 9);
  EXPECT_EQ(set.positions[3], 1 + 4);
  EXPECT_EQ(set.positions[6], 0 + 14);
  EXPECT_EQ(set.positions[9], 0.25f + (0.75f * 8 + 0.25f * 16) * 0.25f);
}

TEST(MotionApplicationTest, NonFiniteOutputLeavesGaussianUnchanged) {
  const GridConfig config = MakeConfig({1}, {2});
  const MotionGrid grid = ZeroGrid(config);
  MlpWeights mlp;
  mlp.layers = MlpShapes(1, MlpConfig{1, 2});
  mlp.layers[0].biases = {3e38f, 1};
  mlp.layers[1].weights[2 * 6] = 10;  // o[6] = 3e39 = inf
  mlp.layers[1].biases[0] = 1;
  GaussianSet set = MakeSet({0.5f, 0.5f, 0.5f}, {0, 0, 0, 1});
  const GaussianSet original = set;
  ApplyMotion(config, grid, mlp, &set);
  EXPECT_EQ(set.positions, original.positions);
  EXPECT_EQ(set.rotations, original.rotations);
}

// Random grids, weights and sets in which every path of 6.3 occurs.
struct RandomCase {
  GridConfig config;
  MotionGrid grid;
  MlpWeights mlp;
  GaussianSet set;
};

float Pick(std::mt19937* rng, std::vector<float> choices) {
  return choices[std::uniform_int_distribution<size_t>(0, choices.size() - 1)(*rng)];
}

RandomCase MakeRandomCase(std::mt19937* rng, bool paper, size_t count) {
  RandomCase rc;
  std::uniform_int_distribution<int> levels(1, kMaxGridLevels), channels(1, kMaxGridChannels),
      resolution(2, 24), hidden(1, kMaxMlpHiddenLayers), width(1, 70);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  MlpConfig mlp_config{1, 64};
  if (paper) {
    rc.config = MakeConfig({4, 4, 2}, {32, 64, 128});
  } else {
    rc.config.num_levels = levels(*rng);
    for (int l = 0; l < rc.config.num_levels; ++l) {
      rc.config.channels[l] = channels(*rng);
      rc.config.resolution[l] = resolution(*rng);
    }
    mlp_config = MlpConfig{hidden(*rng), width(*rng)};
  }

  // Grid: mostly small values, some at the int16 extremes; steps of every kind.
  MotionGrid& grid = rc.grid;
  std::uniform_int_distribution<int> small(-300, 300), full(-32768, 32767);
  for (int l = 0; l < rc.config.num_levels; ++l) {
    grid.values[l].resize(rc.config.level_values(l));
    for (int16_t& v : grid.values[l]) {
      const float kind = unit(*rng);
      v = static_cast<int16_t>(kind < 0.4f ? 0 : kind < 0.9f ? small(*rng) : full(*rng));
    }
    grid.step[l] = Pick(rng, {1.0f / 64, 0.01f, 1e-3f, -0.3f, 0.0f, 7.0f, 1e-40f});
  }
  for (int a = 0; a < 3; ++a) {
    grid.box_min[a] = Pick(rng, {-1.0f, -2.5f, 0.1f, -0.7f});
    grid.box_scale[a] = Pick(rng, {0.5f, 0.25f, 1.0f / 3, 0.37f});
  }

  // MLP: float(q) * step as decoded; a large step overflows some Gaussians to infinity.
  rc.mlp.layers = MlpShapes(rc.config.feature_count(), mlp_config);
  std::uniform_int_distribution<int> q(-2047, 2047);
  for (MlpLayer& layer : rc.mlp.layers) {
    const float w_step = Pick(rng, {1e-3f, 3e-4f, 1e-2f, 1e-5f});
    const float b_step = Pick(rng, {1e-3f, 1e-4f, 0.05f});
    for (float& w : layer.weights) w = static_cast<float>(q(*rng)) * w_step;
    for (float& b : layer.biases) b = static_cast<float>(q(*rng)) * b_step;
  }
  if (unit(*rng) < 0.3f) {
    for (float& w : rc.mlp.layers[0].weights) w = w * 1e34f;
  }

  // Gaussians inside, outside, on the faces (u exactly 0 and 1), non-finite; quaternions
  // random, zero, tiny and huge.
  std::vector<float> positions(3 * count), rotations(4 * count);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (size_t i = 0; i < count; ++i) {
    for (int a = 0; a < 3; ++a) {
      const float extent = 1.0f / grid.box_scale[a];
      const float kind = unit(*rng);
      float p;
      if (kind < 0.7f) {
        p = grid.box_min[a] + unit(*rng) * extent;
      } else if (kind < 0.8f) {
        p = grid.box_min[a];
      } else if (kind < 0.87f) {
        p = grid.box_min[a] + extent;  // u is 1 or just off it
      } else if (kind < 0.97f) {
        p = grid.box_min[a] + (unit(*rng) * 3 - 1) * extent;
      } else {
        p = Pick(rng, {kInf, -kInf, kNaN, 3e38f});
      }
      positions[3 * i + a] = p;
    }
    const float kind = unit(*rng);
    for (int k = 0; k < 4; ++k) {
      rotations[4 * i + k] = kind < 0.85f   ? normal(*rng)
                             : kind < 0.9f  ? 0.0f
                             : kind < 0.95f ? normal(*rng) * 1e-16f
                                            : normal(*rng) * 1e20f;
    }
  }
  rc.set = MakeSet(positions, rotations);
  return rc;
}

GaussianSet Prefix(const GaussianSet& set, size_t count) {
  return MakeSet(std::vector<float>(set.positions.begin(), set.positions.begin() + 3 * count),
                 std::vector<float>(set.rotations.begin(), set.rotations.begin() + 4 * count));
}

bool SameBits(const Buffer<float>& a, const Buffer<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST(MotionApplicationTest, AThreadPoolGivesTheSameBits) {
  std::mt19937 rng(11);
  ThreadPool pool(3);
  for (int trial = 0; trial < 4; ++trial) {
    const RandomCase rc = MakeRandomCase(&rng, trial == 0, 20000);
    GaussianSet alone = rc.set, pooled = rc.set;
    ApplyMotion(rc.config, rc.grid, rc.mlp, &alone);
    ApplyMotion(rc.config, rc.grid, rc.mlp, &pooled, &pool);
    ASSERT_TRUE(SameBits(pooled.positions, alone.positions)) << "trial " << trial;
    ASSERT_TRUE(SameBits(pooled.rotations, alone.rotations)) << "trial " << trial;
    ASSERT_FALSE(SameBits(alone.positions, rc.set.positions)) << "nothing moved";
  }
}

TEST(MotionApplicationTest, BitIdenticalToReference) {
  std::mt19937 rng(7);
  size_t moved = 0, outside = 0, non_finite = 0, identity = 0, on_face = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const RandomCase rc = MakeRandomCase(&rng, trial % 20 == 0, 1000);
    for (size_t count : {0, 1, 15, 16, 17, 1000}) {
      const GaussianSet input = Prefix(rc.set, count);
      GaussianSet expected = input;
      ReferenceApplyMotion(rc.config, rc.grid, rc.mlp, &expected);
      // Every kernel this CPU runs, and the dispatcher, give the reference's bits.
      for (MotionKernelKind kind : {MotionKernelKind::kBaseline, MotionKernelKind::kAvx512}) {
        if (!MotionKernelSupported(kind)) continue;
        GaussianSet other = input;
        ApplyMotionWith(kind, rc.config, rc.grid, rc.mlp, &other);
        ASSERT_TRUE(SameBits(other.positions, expected.positions))
            << "kernel " << static_cast<int>(kind) << " trial " << trial << " count " << count;
        ASSERT_TRUE(SameBits(other.rotations, expected.rotations))
            << "kernel " << static_cast<int>(kind) << " trial " << trial << " count " << count;
      }
      GaussianSet actual = input;
      ApplyMotion(rc.config, rc.grid, rc.mlp, &actual);
      ASSERT_TRUE(SameBits(actual.positions, expected.positions))
          << "trial " << trial << " count " << count;
      ASSERT_TRUE(SameBits(actual.rotations, expected.rotations))
          << "trial " << trial << " count " << count;
      ASSERT_EQ(actual.log_scales, input.log_scales);
      ASSERT_EQ(actual.sh, input.sh);

      // Coverage of the paths.
      for (size_t i = 0; i < count; ++i) {
        bool in = true, face = false;
        for (int a = 0; a < 3; ++a) {
          const float u = (input.positions[3 * i + a] - rc.grid.box_min[a]) * rc.grid.box_scale[a];
          in = in && u >= 0 && u <= 1;
          face = face || u == 0 || u == 1;
        }
        const bool changed =
            std::memcmp(&actual.positions[3 * i], &input.positions[3 * i], 3 * sizeof(float)) !=
                0 ||
            std::memcmp(&actual.rotations[4 * i], &input.rotations[4 * i], 4 * sizeof(float)) != 0;
        outside += !in;
        non_finite += in && !changed;
        moved += changed;
        on_face += changed && face;
        identity += changed && actual.rotations[4 * i] == 1 && actual.rotations[4 * i + 1] == 0 &&
                    actual.rotations[4 * i + 2] == 0 && actual.rotations[4 * i + 3] == 0;
      }
    }
  }
  EXPECT_GT(moved, 10000u);
  EXPECT_GT(outside, 1000u);
  EXPECT_GT(non_finite, 1000u);
  EXPECT_GT(identity, 100u);
  EXPECT_GT(on_face, 1000u);
}

}  // namespace
}  // namespace m4d
