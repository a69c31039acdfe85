// The steps of spec 6.3 that the syntax walk of spec_coverage_test.cc cannot see, checked on
// the conformance stream written for them (synth_edge_cases, m4d_synth --edge-cases): before
// each MOTION_GRID a scalar evaluation of steps 1 to 3 finds the Gaussians on an upper face of
// the box, with degenerate rotations and with non-finite MLP outputs; each kind must occur,
// and the SDK's moved set must show its branch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/decode/decoder.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_grid.h"
#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

// As the SDK: no contraction into FMA, whatever the flags (see motion_test.cc).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off", "no-tree-vectorize")
#endif

// Spec 6.3 steps 2 and 3 at box coordinates u. With `clamp` false, t is taken before the
// clamp of the cell index: at u = 1 the features read corner R - 2 instead of R - 1.
std::vector<float> Outputs(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                           const float u[3], bool clamp) {
  std::vector<float> x;
  for (int l = 0; l < config.num_levels; ++l) {
    const int r = config.resolution[l], channels = config.channels[l];
    int i[3];
    float w[3][2];
    for (int a = 0; a < 3; ++a) {
      const float g = u[a] * static_cast<float>(r - 1);
      const int cell = static_cast<int>(std::trunc(g));
      i[a] = std::min(cell, r - 2);
      const float t = g - static_cast<float>(clamp ? i[a] : cell);
      w[a][0] = 1 - t;
      w[a][1] = t;
    }
    for (int c = 0; c < channels; ++c) {
      float acc = 0;
      for (int k = 0; k < 8; ++k) {
        const int dx = k & 1, dy = (k >> 1) & 1, dz = (k >> 2) & 1;
        const size_t index =
            ((static_cast<size_t>(i[2] + dz) * r + (i[1] + dy)) * r + (i[0] + dx)) * channels + c;
        acc = acc + ((w[0][dx] * w[1][dy]) * w[2][dz]) * static_cast<float>(grid.values[l][index]);
      }
      x.push_back(acc * grid.step[l]);
    }
  }
  for (size_t j = 0; j < mlp.layers.size(); ++j) {
    const MlpLayer& layer = mlp.layers[j];
    std::vector<float> y(layer.outputs);
    for (int o = 0; o < layer.outputs; ++o) {
      float acc = layer.biases[o];
      for (int in = 0; in < layer.inputs; ++in) {
        acc = acc + layer.weights[o * layer.inputs + in] * x[in];
      }
      y[o] = j + 1 < mlp.layers.size() && !(acc > 0) ? acc * kLeakyReluSlope : acc;
    }
    x = y;
  }
  return x;
}

// n2 of spec 6.3 step 6 for outputs o and rotation q.
float RotationNorm2(const std::vector<float>& o, const float* q) {
  const float dw = 1 + o[3], dx = o[4], dy = o[5], dz = o[6];
  const float rw = ((dw * q[0] - dx * q[1]) - dy * q[2]) - dz * q[3];
  const float rx = ((dw * q[1] + dx * q[0]) + dy * q[3]) - dz * q[2];
  const float ry = ((dw * q[2] - dx * q[3]) + dy * q[0]) + dz * q[1];
  const float rz = ((dw * q[3] + dx * q[2]) - dy * q[1]) + dz * q[0];
  return ((rw * rw + rx * rx) + ry * ry) + rz * rz;
}

#if !defined(__clang__) && defined(__GNUC__)
#pragma GCC pop_options
#endif

// How often each branch occurred.
struct Branches {
  int on_face = 0;   // a u exactly 1, outputs finite and depending on the clamped corner
  int zero = 0;      // n2 = 0
  int tiny = 0;      // 0 < n2 <= 1e-30
  int infinite = 0;  // n2 infinite, outputs finite
  int non_finite = 0;
  int moved = 0;  // finite outputs, n2 normal
};

// Classifies every Gaussian of `before` and checks the SDK's moved set `after` against it.
void Check(const SequenceHeader& seq, const MotionGrid& grid, const MlpWeights& mlp,
           const GaussianSet& before, const GaussianSet& after, Branches* b) {
  ASSERT_EQ(before.size(), after.size());
  for (size_t i = 0; i < before.size(); ++i) {
    const float* p = &before.positions[3 * i];
    const float* q = &before.rotations[4 * i];
    float u[3];
    bool inside = true, on_face = false;
    for (int a = 0; a < 3; ++a) {
      u[a] = (p[a] - grid.box_min[a]) * grid.box_scale[a];
      inside = inside && u[a] >= 0 && u[a] <= 1;
      on_face = on_face || u[a] == 1;
    }
    if (!inside) continue;
    const std::vector<float> o = Outputs(seq.grid, grid, mlp, u, true);
    bool finite = true;
    for (float v : o) finite = finite && std::isfinite(v);
    const float* moved_p = &after.positions[3 * i];
    const float* moved_q = &after.rotations[4 * i];
    if (!finite) {
      ++b->non_finite;
      EXPECT_TRUE(std::equal(p, p + 3, moved_p) && std::equal(q, q + 4, moved_q)) << i;
      continue;
    }
    for (int a = 0; a < 3; ++a) EXPECT_EQ(moved_p[a], p[a] + o[a]) << i;
    if (on_face && o != Outputs(seq.grid, grid, mlp, u, false)) ++b->on_face;
    const float n2 = RotationNorm2(o, q);
    if (n2 > 1e-30f && std::isfinite(n2)) {
      ++b->moved;
      continue;
    }
    ++(n2 == 0 ? b->zero : n2 > 0 && n2 <= 1e-30f ? b->tiny : b->infinite);
    EXPECT_EQ(std::vector<float>(moved_q, moved_q + 4), std::vector<float>({1, 0, 0, 0})) << i;
  }
}

TEST(MotionEdgeCases, EveryBranchOccursInTheConformanceStream) {
  std::ifstream file(std::string(M4D_SOURCE_DIR) + "/conformance/streams/synth_edge_cases.m4d",
                     std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  ASSERT_FALSE(bytes.empty());
  Decoder decoder{DecoderOptions()};
  MlpWeights mlp;
  Branches b;
  for (const Packet& packet : SplitPackets(bytes)) {
    const uint8_t type = packet[4];
    const SequenceHeader& seq = decoder.sequence_header();
    ByteReader payload(packet.data() + 24, packet.size() - 24);
    const GaussianSet* dynamic_set = decoder.dynamic_set();
    if (type == M4D_PACKET_MLP_WEIGHTS) {
      ASSERT_TRUE(
          ReadMlpWeights(&payload, seq.rans_layout(), seq.grid.feature_count(), seq.mlp, &mlp)
              .ok());
    }
    MotionGrid grid;
    GaussianSet before;
    if (type == M4D_PACKET_MOTION_GRID) {
      const Status read =
          seq.codes_active_voxels()
              ? ReadActiveMotionGrid(&payload, seq.rans_layout(), seq.grid,
                                     dynamic_set->positions.data(), dynamic_set->size(), &grid)
              : ReadMotionGrid(&payload, seq.rans_layout(), seq.grid, &grid);
      ASSERT_TRUE(read.ok()) << read.message();
      before = *dynamic_set;
    }
    ASSERT_TRUE(decoder.SendPacket(packet.data(), packet.size()).ok());
    if (type == M4D_PACKET_MOTION_GRID) {
      Check(seq, grid, mlp, before, *decoder.dynamic_set(), &b);
    }
    if (decoder.HasFrame()) decoder.TakeFrame();
  }
  EXPECT_GT(b.on_face, 0);
  EXPECT_GT(b.zero, 0);
  EXPECT_GT(b.tiny, 0);
  EXPECT_GT(b.infinite, 0);
  EXPECT_GT(b.non_finite, 0);
  EXPECT_GT(b.moved, b.non_finite);
  std::printf("on face %d, n2 zero %d, tiny %d, infinite %d, non-finite outputs %d, moved %d\n",
              b.on_face, b.zero, b.tiny, b.infinite, b.non_finite, b.moved);
}

}  // namespace
}  // namespace testing
}  // namespace m4d
