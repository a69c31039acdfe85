// Lanes: eight floats processed together (eight pixels of a tile row), as GCC/clang generic
// vectors. Each lane performs exactly the scalar IEEE operation sequence, so a vectorised
// loop gives the same bits as a scalar one when floating-point contraction is off.
#ifndef M4D_SDK_RENDER_LANES_H_
#define M4D_SDK_RENDER_LANES_H_

#include <cstdint>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace m4d {

constexpr int kLanes = 8;
typedef float Lanes __attribute__((vector_size(32)));
typedef int32_t LaneMask __attribute__((vector_size(32)));  // all ones or zero per lane

inline Lanes Broadcast(float x) { return Lanes{x, x, x, x, x, x, x, x}; }

inline Lanes LoadLanes(const float* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}

inline void StoreLanes(const Lanes& v, float* p) { std::memcpy(p, &v, sizeof(v)); }

// Bit l is set when lane l of m is set.
inline unsigned MaskBits(LaneMask m) {
#if defined(__AVX__)
  return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(m)));
#else
  unsigned bits = 0;
  for (int l = 0; l < kLanes; ++l) bits |= (m[l] != 0 ? 1u : 0u) << l;
  return bits;
#endif
}

inline bool AnyLane(LaneMask m) { return MaskBits(m) != 0; }
inline bool AllLanes(LaneMask m) { return MaskBits(m) == (1u << kLanes) - 1; }

// Sum of the eight lanes, in a fixed order.
inline float LaneSum(const Lanes& v) {
  const float a = (v[0] + v[4]) + (v[2] + v[6]);
  const float b = (v[1] + v[5]) + (v[3] + v[7]);
  return a + b;
}

}  // namespace m4d

#endif  // M4D_SDK_RENDER_LANES_H_
