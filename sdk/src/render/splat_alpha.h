// The opacity of a projected Gaussian (a splat) at a pixel, with the rules of the reference
// 3DGS rasterizer:
//   power = -0.5 (a dx^2 + c dy^2) - b dx dy,  (dx, dy) = splat mean - pixel centre,
//   alpha = min(0.99, opacity * exp(power)), skipped when power > 0 or alpha < 1/255,
// and a pixel stops before the splat that would take its transmittance below 1e-4.
//
// The forward pass (SDK) and the backward pass (encoder) both evaluate alpha with these
// functions, and both are compiled without floating-point contraction, so the backward
// recomputes every alpha and every skip decision bit for bit. exp is a polynomial rather
// than the C library's so that it vectorises and gives the same bits everywhere.
#ifndef M4D_SDK_RENDER_SPLAT_ALPHA_H_
#define M4D_SDK_RENDER_SPLAT_ALPHA_H_

#include <cstdint>
#include <cstring>

#include "sdk/src/render/lanes.h"

namespace m4d {

constexpr float kMaxAlpha = 0.99f;
constexpr float kMinAlpha = 1.0f / 255.0f;
constexpr float kMinTransmittance = 0.0001f;

inline int32_t FloatBits(float x) {
  int32_t i;
  std::memcpy(&i, &x, sizeof(i));
  return i;
}
inline float BitsToFloat(int32_t i) {
  float x;
  std::memcpy(&x, &i, sizeof(x));
  return x;
}
inline LaneMask FloatBits(Lanes x) { return reinterpret_cast<LaneMask>(x); }
inline Lanes BitsToFloat(LaneMask i) { return reinterpret_cast<Lanes>(i); }

inline float ClampExpArgument(float x) { return x < -87.0f ? -87.0f : (x > 0.0f ? 0.0f : x); }
inline Lanes ClampExpArgument(Lanes x) {
  x = x < -87.0f ? Broadcast(-87.0f) : x;
  return x > 0.0f ? Lanes{} : x;
}

// exp(x) for x <= 0 (arguments are clamped to [-87, 0]), relative error below 2e-7:
// x = n ln2 + r with |r| <= ln2 / 2, exp(r) by a degree-7 minimax-type polynomial, times 2^n.
// V is float or Lanes.
template <typename V>
V ExpNonPositive(V x) {
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: adding it rounds to an integer
  x = ClampExpArgument(x);
  const V shifted = x * 1.44269504088896341f + kRound;
  const V n = shifted - kRound;
  V r = x - n * 0.693359375f;
  r = r - n * -2.12194440e-4f;
  const V z = r * r;
  V p = 1.9875691500e-4f * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * z + r + 1.0f;
  // 2^n from the integer n held in the low mantissa bits of `shifted`.
  const auto exponent = (FloatBits(shifted) - FloatBits(kRound) + 127) << 23;
  return p * BitsToFloat(exponent);
}

// The Gaussian's exponent at offset (dx, dy) for the conic [[a, b], [b, c]]. dy is shared by
// the eight pixels of a row group, so its terms are scalars.
template <typename V>
V SplatPower(V dx, float dy, float a, float b, float c) {
  return -0.5f * (a * dx * dx + (c * dy) * dy) - (b * dy) * dx;
}

}  // namespace m4d

#endif  // M4D_SDK_RENDER_SPLAT_ALPHA_H_
