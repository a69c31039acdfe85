// Value noise: smooth, tileable pseudo-random patterns for the procedural textures.
#ifndef M4D_ENCODER_SYNTHETIC_VALUE_NOISE_H_
#define M4D_ENCODER_SYNTHETIC_VALUE_NOISE_H_

#include <cstdint>

namespace m4d {

// Smoothly interpolated lattice values in [0, 1) at (x, y) in lattice units; the lattice
// repeats every period_x cells along x and period_y along y, so a texture that spans whole
// periods tiles. Different periods give streaks (wood grain, brushed metal).
float ValueNoise(uint64_t seed, float x, float y, int period_x, int period_y);

// Sum of `octaves` octaves of ValueNoise, each of twice the frequency and half the
// amplitude of the last, normalised to [0, 1).
float FractalNoise(uint64_t seed, float x, float y, int period_x, int period_y, int octaves);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_VALUE_NOISE_H_
