// The lane sums of eight Lanes vectors at once (a transpose-and-add), for the backward
// pass's per-splat reductions: eight horizontal sums for about the price of two.
#ifndef M4D_ENCODER_RASTER_LANE_SUMS_H_
#define M4D_ENCODER_RASTER_LANE_SUMS_H_

#include "sdk/src/render/lanes.h"

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace m4d {

// Lane i of the result is the sum of the lanes of v[i].
inline Lanes LaneSums8(const Lanes v[8]) {
#if defined(__AVX__)
  __m256 m[8];
  for (int i = 0; i < 8; ++i) m[i] = reinterpret_cast<__m256>(v[i]);
  const __m256 t0 = _mm256_hadd_ps(m[0], m[1]), t1 = _mm256_hadd_ps(m[2], m[3]);
  const __m256 t2 = _mm256_hadd_ps(m[4], m[5]), t3 = _mm256_hadd_ps(m[6], m[7]);
  // Per 128-bit half: partial sums of v0..v3 (u0) and v4..v7 (u1).
  const __m256 u0 = _mm256_hadd_ps(t0, t1), u1 = _mm256_hadd_ps(t2, t3);
  const __m256 low = _mm256_permute2f128_ps(u0, u1, 0x20);
  const __m256 high = _mm256_permute2f128_ps(u0, u1, 0x31);
  return reinterpret_cast<Lanes>(_mm256_add_ps(low, high));
#else
  Lanes sums;
  for (int i = 0; i < 8; ++i) sums[i] = LaneSum(v[i]);
  return sums;
#endif
}

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_LANE_SUMS_H_
