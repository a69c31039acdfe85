// Synthetic codec content (random Gaussian sets, smooth sparse motion grids, small MLPs) for
// tests, benchmarks, fuzz seeds and the stream demo. Deterministic for a seed on every
// platform: it uses its own generator, not the implementation-defined std distributions.
#ifndef M4D_ENCODER_SYNTHETIC_SYNTHETIC_CONTENT_H_
#define M4D_ENCODER_SYNTHETIC_SYNTHETIC_CONTENT_H_

#include <cstdint>

#include "encoder/src/layers/motion_grid_writer.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

// xorshift64* with uniform floats from the top 24 bits.
class SyntheticRandom {
 public:
  explicit SyntheticRandom(uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 1) {}
  uint64_t Next() {
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return state_ * 0x2545F4914F6CDD1Dull;
  }
  float Uniform() { return static_cast<float>(Next() >> 40) * (1.0f / 16777216.0f); }
  float Uniform(float lo, float hi) { return lo + (hi - lo) * Uniform(); }

 private:
  uint64_t state_;
};

// n Gaussians scattered on the surface of a sphere (center, radius) with plausible scales,
// opacities, rotations and smooth SH colours.
GaussianSet SyntheticGaussianSet(size_t n, int sh_degree, uint64_t seed, const float center[3],
                                 float radius);

// A motion grid over the box [lo, hi]^3 that is zero except for a smooth blob of motion
// covering about `blob_fraction` of the box (what rate-aware training produces).
FloatMotionGrid SyntheticMotionGrid(const GridConfig& config, uint64_t seed, float lo, float hi,
                                    float blob_fraction);

// An MLP with small random weights: moves Gaussians by a few millimetres per unit feature.
MlpWeights SyntheticMlp(int feature_count, const MlpConfig& config, uint64_t seed);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SYNTHETIC_CONTENT_H_
