#include "encoder/src/synthetic/synthetic_edge_cases.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/synthetic/synthetic_content.h"

namespace m4d {

namespace {

// Edge-case content. Every level has 9 nodes per axis over the nominal box [0, 2]^3: node k at
// 0.25 k. Level 0 moves the Gaussians; levels 1 and 2 have a tiny and a huge step (no one step
// serves both and the motion) and are zero outside the cells of the Gaussians they are for.
constexpr int kEdgeResolution = 9;
constexpr float kEdgeExtent = 2.0f;
constexpr int kEdgeChannels[] = {4, 1, 2};
constexpr float kEdgeSteps[] = {1.0f / 300, 3e-20f, 2e35f};  // none a power of two
constexpr int kEdgeFeatures = 7;

// Where a Gaussian of the edge-case set lies. The special ones share the column of x cell 5
// (x in [1.25, 1.5], nodes 5 and 6), where level 0 is zero, one y cell each (every other
// cell, so that no two share a node). Three in eight Gaussians are simply moved.
enum class EdgeRole { kMoved, kOnFace, kZeroRotation, kTinyRotation, kHugeRotation, kOverflow };
constexpr EdgeRole kEdgeRoles[] = {
    EdgeRole::kMoved, EdgeRole::kOnFace,       EdgeRole::kZeroRotation, EdgeRole::kTinyRotation,
    EdgeRole::kMoved, EdgeRole::kHugeRotation, EdgeRole::kOverflow,     EdgeRole::kMoved};
constexpr float kEdgeColumnX = 1.375f;

bool InSpecialColumn(int x) { return x == 5 || x == 6; }

// Quantized value of channel c of level l at node (x, y, z).
int EdgeGridValue(int l, int c, int x, int y, int z, SyntheticRandom* rng) {
  if (l == 0) {
    // Random motion everywhere but the special column; channel 3 makes d_w = 1 + o[3] near 1.
    if (InSpecialColumn(x)) return 0;
    const int r = static_cast<int>(rng->Next() % 81);
    return c < 3 ? 6 * (r - 40) : 260 + r;
  }
  if (!InSpecialColumn(x)) return 0;
  if (l == 1) return y == 2 || y == 3 ? 1000 + 100 * z : 0;  // 3e-17 to 5.4e-17: tiny d
  if (y == 4 || y == 5) return c == 0 ? 100 : 0;             // 2e37: n2 overflows
  return y == 6 || y == 7 ? 1600 : 0;  // 3.2e38 twice: their sum o[4] overflows
}

// Position of Gaussian i of the edge-case set.
void PlaceEdgeCase(size_t i, SyntheticRandom* rng, float* p) {
  const EdgeRole role = kEdgeRoles[i % 8];
  if (i == 0) {  // the upper corner: clamped on every axis
    std::fill(p, p + 3, kEdgeExtent);
    return;
  }
  if (role == EdgeRole::kMoved || role == EdgeRole::kOnFace) {
    p[0] = rng->Uniform(0.05f, 1.0f);  // x nodes 0 to 4
    p[1] = rng->Uniform(0.05f, 1.95f);
    p[2] = rng->Uniform(0.05f, 1.95f);
    if (role == EdgeRole::kOnFace) p[(i / 8) % 3] = kEdgeExtent;
    return;
  }
  // y cells 0, 2, 4, 6 (centres 0.125, 0.625, 1.125, 1.625).
  const int cell = 2 * (static_cast<int>(role) - static_cast<int>(EdgeRole::kZeroRotation));
  p[0] = kEdgeColumnX + rng->Uniform(-0.05f, 0.05f);
  p[1] = 0.25f * static_cast<float>(cell) + 0.125f + rng->Uniform(-0.05f, 0.05f);
  p[2] = rng->Uniform(0.05f, 1.95f);
}

}  // namespace

GridConfig EdgeCaseGridConfig() {
  GridConfig config;
  config.num_levels = 3;
  for (int l = 0; l < config.num_levels; ++l) {
    config.resolution[l] = kEdgeResolution;
    config.channels[l] = kEdgeChannels[l];
  }
  return config;
}

MlpConfig EdgeCaseMlpConfig() { return MlpConfig{1, kEdgeFeatures + 1}; }

GaussianSet EdgeCaseGaussianSet(size_t n, int sh_degree, uint64_t seed) {
  const float center[3] = {1, 1, 1};
  GaussianSet set = SyntheticGaussianSet(n, sh_degree, seed, center, 0.5f);
  SyntheticRandom rng(seed);
  for (size_t i = 0; i < n; ++i) PlaceEdgeCase(i, &rng, &set.positions[3 * i]);
  // Constant groups with -0 mins, which spec 5.4 decodes to +0: opacities -0, higher SH -0
  // and +0 in turn.
  std::fill(set.opacity_logits.begin(), set.opacity_logits.end(), -0.0f);
  const size_t floats = static_cast<size_t>(set.sh_floats());
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 3; k < floats; ++k) set.sh[i * floats + k] = k % 2 == 0 ? -0.0f : 0.0f;
  }
  return set;
}

MlpWeights EdgeCaseMlp() {
  MlpWeights mlp;
  mlp.layers = MlpShapes(kEdgeFeatures, EdgeCaseMlpConfig());
  // Hidden units 0-6 pass the features on, unit 7 is a constant 0.37.
  MlpLayer& hidden = mlp.layers[0];
  for (int i = 0; i < kEdgeFeatures; ++i) hidden.weights[i * kEdgeFeatures + i] = 1.0f;
  hidden.biases[kEdgeFeatures] = 0.37f;
  // o[0..2]: 0.02 times the motion features plus a constant drift; o[3] = h3 - 1, so that
  // d_w = 1 + o[3] is 0 where level 0 is; o[4] = 0.2 h0 + h4 + h5 + h6 (tiny, huge, overflow),
  // o[5], o[6] = 0.2 h1, 0.2 h2. The steps come out as 1/2047 and 0.37/2047.
  MlpLayer& out = mlp.layers[1];
  const int in = kEdgeFeatures + 1;
  auto w = [&](int o, int i) -> float& { return out.weights[o * in + i]; };
  for (int a = 0; a < 3; ++a) w(a, a) = 0.02f;
  w(0, kEdgeFeatures) = 0.02f;
  w(3, 3) = 1.0f;
  w(4, 0) = w(5, 1) = w(6, 2) = 0.2f;
  w(4, 4) = w(4, 5) = w(4, 6) = 1.0f;
  out.biases = {0.004f, -0.003f, 0.002f, -1.0f, 0.0f, 0.0f, 0.0f};
  return mlp;
}

FloatMotionGrid EdgeCaseMotionGrid(uint64_t seed, const GaussianSet& dynamic_set) {
  FloatMotionGrid grid;
  for (int a = 0; a < 3; ++a) {
    // The upper face through the farthest Gaussian (the nominal one for an empty set): top - 2
    // is exact for top in [1, 4] (Sterbenz), so there (top - box_min) * 0.5 is 1 exactly.
    float top = dynamic_set.size() > 0 ? dynamic_set.positions[a] : kEdgeExtent;
    for (size_t i = 1; i < dynamic_set.size(); ++i) {
      top = std::max(top, dynamic_set.positions[3 * i + a]);
    }
    grid.box_min[a] = top - kEdgeExtent;
    grid.box_scale[a] = 1.0f / kEdgeExtent;
  }
  const GridConfig config = EdgeCaseGridConfig();
  SyntheticRandom rng(seed);
  const int r = kEdgeResolution;
  for (int l = 0; l < config.num_levels; ++l) {
    grid.step[l] = kEdgeSteps[l];
    grid.values[l].clear();
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          for (int c = 0; c < config.channels[l]; ++c) {
            const int q = EdgeGridValue(l, c, x, y, z, &rng);
            grid.values[l].push_back(static_cast<float>(q) * kEdgeSteps[l]);
          }
        }
      }
    }
  }
  return grid;
}

}  // namespace m4d
