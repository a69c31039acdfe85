// Deterministic pseudo-random numbers for the synthetic scene: a counter-based hash, so that
// every value depends only on (seed, stream, index) and the scene is the same on every
// platform and standard library (std:: distributions are not).
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_RANDOM_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_RANDOM_H_

#include <cstdint>

namespace m4d {

// SplitMix64's finaliser: a well-mixed 64-bit hash of x.
inline uint64_t MixBits(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A sequence of uniform numbers; the same seed gives the same sequence.
class SceneRandom {
 public:
  explicit SceneRandom(uint64_t seed) : state_(MixBits(seed)) {}
  uint64_t Next() { return MixBits(state_++); }
  // Uniform in [0, 1), 24 bits.
  float Uniform() { return static_cast<float>(Next() >> 40) * (1.0f / 16777216.0f); }
  float Uniform(float low, float high) { return low + (high - low) * Uniform(); }

 private:
  uint64_t state_;
};

// Uniform in [0, 1) from a hash of (seed, x, y): a lattice of independent values.
inline float LatticeValue(uint64_t seed, int64_t x, int64_t y) {
  const uint64_t h = MixBits(
      seed ^ MixBits(static_cast<uint64_t>(x) * 0x632BE59BD9B4E019ull + static_cast<uint64_t>(y)));
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_RANDOM_H_
