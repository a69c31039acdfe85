// The motion kernel: spec 6.3 for a whole dynamic set. This file is compiled once for the
// baseline target and, on x86-64, once more with AVX-512 (M4D_MOTION_KERNEL_NAME names each
// build's entry point); motion_application.cc picks one at run time. Both perform the same
// IEEE operations lane by lane, so their results are bit-identical.
#include "sdk/src/decode/motion_kernel.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "sdk/src/common/spec_limits.h"

#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

namespace m4d {
namespace {

// Gaussians are evaluated kLanes at a time, one per lane of GCC/clang generic vectors. Each
// lane performs exactly the scalar operation sequence of spec 6.3 in IEEE binary32 (the SDK is
// built with -ffp-contract=off), so the result is bit-identical to a one-at-a-time decoder.
// Vectors are as wide as the target's registers (wider generic vectors compile badly); a
// block is two of them, which gives the MLP independent chains to interleave.
#if defined(__AVX512F__)
constexpr int kVectorBytes = 64;
#elif defined(__AVX__)
constexpr int kVectorBytes = 32;
#else
constexpr int kVectorBytes = 16;
#endif
typedef float Vec __attribute__((vector_size(kVectorBytes)));
typedef int32_t VecI __attribute__((vector_size(kVectorBytes)));
constexpr int kWidth = kVectorBytes / sizeof(float);
constexpr int kVecs = 2;
constexpr int kLanes = kWidth * kVecs;

// Up to 4 channels of one voxel, one channel per lane.
typedef int32_t Int32x4 __attribute__((vector_size(16)));
typedef float Floatx4 __attribute__((vector_size(16)));

// One float per lane of a block.
struct alignas(kVectorBytes) Lanes {
  float f[kLanes];
};

Vec Load(const Lanes& lanes, int v) {
  Vec r;
  std::memcpy(&r, lanes.f + v * kWidth, sizeof(r));
  return r;
}
void Store(const Vec& value, int v, Lanes* lanes) {
  std::memcpy(lanes->f + v * kWidth, &value, sizeof(value));
}
// All-ones lanes where x is finite (false for NaN and infinities).
VecI Finite(const Vec& x) { return (x >= -FLT_MAX) & (x <= FLT_MAX); }

// N (1..4) channels of a voxel, widened to int32. Written out so that compilers emit a
// single sign-extending load for 4 channels.
template <int N>
Int32x4 LoadChannels(const int16_t* v) {
  if constexpr (N >= 4) return Int32x4{v[0], v[1], v[2], v[3]};
  if constexpr (N == 3) return Int32x4{v[0], v[1], v[2], 0};
  if constexpr (N == 2) return Int32x4{v[0], v[1], 0, 0};
  return Int32x4{v[0], 0, 0, 0};
}

// Lane l of features[0..N-1] from the channels of one voxel.
template <int N>
void StoreChannels(const Floatx4& channels, int l, Lanes* features) {
#if defined(__wasm_simd128__)
  // Clang otherwise turns the extraction of each channel into scalar code all the way back to
  // the voxel loads; SIMD128 stores a lane directly.
  wasm_v128_store32_lane(features[0].f + l, v128_t(channels), 0);
  if constexpr (N > 1) wasm_v128_store32_lane(features[1].f + l, v128_t(channels), 1);
  if constexpr (N > 2) wasm_v128_store32_lane(features[2].f + l, v128_t(channels), 2);
  if constexpr (N > 3) wasm_v128_store32_lane(features[3].f + l, v128_t(channels), 3);
#else
  for (int c = 0; c < N; ++c) features[c].f[l] = channels[c];
#endif
}

// Exact int -> float conversion of grid values (|v| < 2^22).
Floatx4 ToFloat(const Int32x4& v) {
#if defined(__wasm_simd128__)
  // Clang folds the widening into the conversion and then converts lane by lane on
  // WebAssembly. Adding v to the float 2^23 + 2^22 as integers and subtracting that float
  // is the same exact conversion, kept as three vector operations.
  constexpr int32_t kMagicBits = 0x4B400000;  // 12582912.0f
  Floatx4 biased;
  const Int32x4 bits = v + kMagicBits;
  std::memcpy(&biased, &bits, sizeof(biased));
  return biased - 12582912.0f;
#else
  return __builtin_convertvector(v, Floatx4);
#endif
}

struct Level {
  int resolution;
  int channels;
  float step;
  const int16_t* values;
  int offset[8];  // of corner k from corner 0, in int16 values
};

// Up to kLanes Gaussians that lie in the box; unused lanes hold u = 0 (valid grid indices).
struct Block {
  int count = 0;
  uint32_t index[kLanes];
  Lanes u[3];  // box coordinates x, y, z
  Lanes p[3];  // positions x, y, z
  // Per level, from PrepareLevel: trilinear weight of each corner, index of corner 0.
  Lanes corner_weight[kMaxGridLevels][8];
  alignas(kVectorBytes) int32_t base[kMaxGridLevels][kLanes];
};

// Spec 6.3 step 2 up to the corner weights, for every lane of the block.
void PrepareLevel(const Level& level, int l, Block* block) {
  const int r = level.resolution;
  const VecI max_index = VecI{} + (r - 2);
  for (int v = 0; v < kVecs; ++v) {
    VecI index[3];
    Vec w[3][2];  // w[a][d]: weight of the corner at +d along axis a
    for (int a = 0; a < 3; ++a) {
      const Vec g = Load(block->u[a], v) * static_cast<float>(r - 1);
      const VecI i = __builtin_convertvector(g, VecI);  // trunc, g >= 0
      index[a] = i < max_index ? i : max_index;
      const Vec t = g - __builtin_convertvector(index[a], Vec);
      w[a][0] = 1.0f - t;
      w[a][1] = t;
    }
    for (int k = 0; k < 8; ++k) {
      const Vec wk = (w[0][k & 1] * w[1][(k >> 1) & 1]) * w[2][(k >> 2) & 1];
      Store(wk, v, &block->corner_weight[l][k]);
    }
    const VecI base = ((index[2] * r + index[1]) * r + index[0]) * level.channels;
    std::memcpy(block->base[l] + v * kWidth, &base, sizeof(base));
  }
}

// The feature sums of spec 6.3 step 2. The corners of a Gaussian are scattered over the grid,
// so this part runs Gaussian by Gaussian, with the channels in vector lanes (each lane is one
// channel's own chain of operations).
template <int C>
void LevelFeatures(const Level& level, const Lanes* corner_weight, const int32_t* base,
                   Lanes* features) {
  constexpr int kChunks = (C + 3) / 4;
  for (int l = 0; l < kLanes; ++l) {
    const int16_t* voxel = level.values + base[l];
    Floatx4 acc[kChunks] = {};
    if constexpr (C <= 2) {
      // Corners k and k + 1 (x and x + 1) are adjacent voxels: one load serves both, and
      // the products of the second move down to the accumulator's lanes.
      for (int k = 0; k < 8; k += 2) {
        const Floatx4 v = ToFloat(LoadChannels<2 * C>(voxel + level.offset[k]));
        const Floatx4 first = corner_weight[k].f[l] * v;
        const Floatx4 second = corner_weight[k + 1].f[l] * v;
        acc[0] = acc[0] + first;
        acc[0] = acc[0] + __builtin_shufflevector(second, second, C, C + 1, C + 2, C + 3);
      }
    } else {
      for (int k = 0; k < 8; ++k) {
        const float w = corner_weight[k].f[l];
        const int16_t* v = voxel + level.offset[k];
        acc[0] = acc[0] + w * ToFloat(LoadChannels<C>(v));
        if constexpr (C > 4) {
          acc[1] = acc[1] + w * ToFloat(LoadChannels<C - 4>(v + 4));
        }
      }
    }
    StoreChannels<std::min(C, 4)>(acc[0] * level.step, l, features);
    if constexpr (C > 4) StoreChannels<C - 4>(acc[1] * level.step, l, features + 4);
  }
}

void ComputeFeatures(const Level& level, const Lanes* corner_weight, const int32_t* base,
                     Lanes* features) {
  switch (level.channels) {
    case 1:
      return LevelFeatures<1>(level, corner_weight, base, features);
    case 2:
      return LevelFeatures<2>(level, corner_weight, base, features);
    case 3:
      return LevelFeatures<3>(level, corner_weight, base, features);
    case 4:
      return LevelFeatures<4>(level, corner_weight, base, features);
    case 5:
      return LevelFeatures<5>(level, corner_weight, base, features);
    case 6:
      return LevelFeatures<6>(level, corner_weight, base, features);
    case 7:
      return LevelFeatures<7>(level, corner_weight, base, features);
    default:
      return LevelFeatures<8>(level, corner_weight, base, features);
  }
}

// K consecutive outputs of a linear layer for all lanes (spec 6.3 step 3). The lanes are
// innermost and the K x kVecs accumulators stay in registers while the inputs stream by.
template <int K>
void DenseRows(const float* weights, const float* biases, int inputs, bool leaky, const Lanes* x,
               Lanes* y) {
  Vec acc[K][kVecs];
  for (int k = 0; k < K; ++k) {
    for (int v = 0; v < kVecs; ++v) acc[k][v] = biases[k] + weights[k * inputs] * Load(x[0], v);
  }
  for (int i = 1; i < inputs; ++i) {
    Vec xi[kVecs];
    for (int v = 0; v < kVecs; ++v) xi[v] = Load(x[i], v);
    for (int k = 0; k < K; ++k) {
      const float w = weights[k * inputs + i];
      for (int v = 0; v < kVecs; ++v) acc[k][v] = acc[k][v] + w * xi[v];
    }
  }
  for (int k = 0; k < K; ++k) {
    for (int v = 0; v < kVecs; ++v) {
      const Vec a = acc[k][v];
      Store(leaky ? (a > 0.0f ? a : a * kLeakyReluSlope) : a, v, &y[k]);
    }
  }
}

void Dense(const MlpLayer& layer, bool leaky, const Lanes* x, Lanes* y) {
  const int in = layer.inputs;
  const float* w = layer.weights.data();
  const float* b = layer.biases.data();
  int o = 0;
  for (; o + 4 <= layer.outputs; o += 4) DenseRows<4>(w + o * in, b + o, in, leaky, x, y + o);
  switch (layer.outputs - o) {
    case 3:
      return DenseRows<3>(w + o * in, b + o, in, leaky, x, y + o);
    case 2:
      return DenseRows<2>(w + o * in, b + o, in, leaky, x, y + o);
    case 1:
      return DenseRows<1>(w + o * in, b + o, in, leaky, x, y + o);
    default:
      return;
  }
}

// Spec 6.3 steps 4 to 6 with the outputs o[0..6] of every lane.
void Update(const Block& block, const Lanes* o, GaussianSet* set) {
  float* positions = set->positions.data();
  float* rotations = set->rotations.data();
  Lanes q[4];
  // Unused lanes read the block's first Gaussian: Gaussian 0 may be another task's, being
  // written by another thread (a data race, though the lanes are discarded).
  for (int l = 0; l < kLanes; ++l) {
    const float* src = rotations + 4 * static_cast<size_t>(block.index[l < block.count ? l : 0]);
    for (int c = 0; c < 4; ++c) q[c].f[l] = src[c];
  }
  alignas(kVectorBytes) int32_t finite[kLanes];
  Lanes moved[3], turned[4];
  for (int v = 0; v < kVecs; ++v) {
    VecI all_finite = Finite(Load(o[0], v));
    for (int k = 1; k < kMlpOutputs; ++k) all_finite &= Finite(Load(o[k], v));
    std::memcpy(finite + v * kWidth, &all_finite, sizeof(all_finite));
    for (int a = 0; a < 3; ++a) Store(Load(block.p[a], v) + Load(o[a], v), v, &moved[a]);

    const Vec dw = 1.0f + Load(o[3], v), dx = Load(o[4], v), dy = Load(o[5], v), dz = Load(o[6], v);
    const Vec qw = Load(q[0], v), qx = Load(q[1], v), qy = Load(q[2], v), qz = Load(q[3], v);
    const Vec rw = ((dw * qw - dx * qx) - dy * qy) - dz * qz;
    const Vec rx = ((dw * qx + dx * qw) + dy * qz) - dz * qy;
    const Vec ry = ((dw * qy - dx * qz) + dy * qw) + dz * qx;
    const Vec rz = ((dw * qz + dx * qy) - dy * qx) + dz * qw;
    const Vec n2 = ((rw * rw + rx * rx) + ry * ry) + rz * rz;
    const VecI normal = (n2 > 1e-30f) & Finite(n2);
    Vec n;
    for (int i = 0; i < kWidth; ++i) n[i] = std::sqrt(n2[i]);
    const Vec zero = {}, one = zero + 1.0f;
    Store(normal ? rw / n : one, v, &turned[0]);
    Store(normal ? rx / n : zero, v, &turned[1]);
    Store(normal ? ry / n : zero, v, &turned[2]);
    Store(normal ? rz / n : zero, v, &turned[3]);
  }
  for (int l = 0; l < block.count; ++l) {
    if (!finite[l]) continue;
    float* p = positions + 3 * static_cast<size_t>(block.index[l]);
    for (int a = 0; a < 3; ++a) p[a] = moved[a].f[l];
    float* r = rotations + 4 * static_cast<size_t>(block.index[l]);
    for (int c = 0; c < 4; ++c) r[c] = turned[c].f[l];
  }
}

// Collects in-box Gaussians into blocks and moves them. Two blocks are in flight: the grid
// lines of one are prefetched while the other is computed, which hides most cache misses.
class MotionKernel {
 public:
  MotionKernel(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
               GaussianSet* set)
      : num_levels_(config.num_levels), mlp_(mlp), set_(set) {
    for (int l = 0; l < num_levels_; ++l) {
      Level& level = levels_[l];
      level.resolution = config.resolution[l];
      level.channels = config.channels[l];
      level.step = grid.step[l];
      level.values = grid.values[l].data();
      const int r = level.resolution;
      for (int k = 0; k < 8; ++k) {
        level.offset[k] = (((k >> 2) & 1) * r * r + ((k >> 1) & 1) * r + (k & 1)) * level.channels;
      }
    }
    size_t width = config.feature_count();
    for (const MlpLayer& layer : mlp.layers) width = std::max<size_t>(width, layer.outputs);
    buffers_[0].resize(width);
    buffers_[1].resize(width);
  }

  void Add(size_t index, const float u[3], const float p[3]) {
    Block& block = *filling_;
    const int l = block.count++;
    block.index[l] = static_cast<uint32_t>(index);
    for (int a = 0; a < 3; ++a) {
      block.u[a].f[l] = u[a];
      block.p[a].f[l] = p[a];
    }
    if (block.count == kLanes) Cycle();
  }

  void Finish() {
    if (filling_->count > 0) {
      for (int l = filling_->count; l < kLanes; ++l) {
        for (int a = 0; a < 3; ++a) filling_->u[a].f[l] = filling_->p[a].f[l] = 0.0f;
      }
      Cycle();
    }
    if (pending_->count > 0) Run(*pending_);
  }

 private:
  // Prepares and prefetches the filled block, computes the pending one, swaps them.
  void Cycle() {
    for (int l = 0; l < num_levels_; ++l) {
      const Level& level = levels_[l];
      PrepareLevel(level, l, filling_);
      for (int lane = 0; lane < filling_->count; ++lane) {
        const int16_t* voxel = level.values + filling_->base[l][lane];
        // Into L2 only: a block's corners would evict each other from L1 before use.
        for (int k = 0; k < 8; ++k) __builtin_prefetch(voxel + level.offset[k], 0, 2);
      }
    }
    if (pending_->count > 0) Run(*pending_);
    std::swap(filling_, pending_);
    filling_->count = 0;
  }

  void Run(const Block& block) {
    Lanes* x = buffers_[0].data();
    Lanes* y = buffers_[1].data();
    for (int l = 0, f = 0; l < num_levels_; f += levels_[l].channels, ++l) {
      ComputeFeatures(levels_[l], block.corner_weight[l], block.base[l], x + f);
    }
    const size_t last = mlp_.layers.size() - 1;
    for (size_t j = 0; j <= last; ++j) {
      Dense(mlp_.layers[j], j < last, x, y);
      std::swap(x, y);
    }
    Update(block, x, set_);
  }

  int num_levels_;
  Level levels_[kMaxGridLevels];
  const MlpWeights& mlp_;
  GaussianSet* set_;
  std::vector<Lanes> buffers_[2];
  Block blocks_[2];
  Block* filling_ = &blocks_[0];
  Block* pending_ = &blocks_[1];
};

}  // namespace

void M4D_MOTION_KERNEL_NAME(const GridConfig& config, const MotionGrid& grid, const MlpWeights& mlp,
                            GaussianSet* set, size_t begin, size_t end) {
  if (begin >= end) return;
  MotionKernel kernel(config, grid, mlp, set);
  // Gaussians outside the box stay unchanged (spec 6.3 step 1); the others are packed into
  // full blocks so that no lanes are spent on them.
  const float* positions = set->positions.data();
  for (size_t i = begin; i < end; ++i) {
    const float* p = positions + 3 * i;
    float u[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      u[a] = (p[a] - grid.box_min[a]) * grid.box_scale[a];
      inside = inside && u[a] >= 0 && u[a] <= 1;
    }
    if (inside) kernel.Add(i, u, p);
  }
  kernel.Finish();
}

}  // namespace m4d
