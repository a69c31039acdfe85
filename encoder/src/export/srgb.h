// The sRGB transfer function (IEC 61966-2-1): 3DGS colours are sRGB-encoded display values,
// glTF's vertex colours are linear.
#ifndef M4D_ENCODER_EXPORT_SRGB_H_
#define M4D_ENCODER_EXPORT_SRGB_H_

#include <cmath>

namespace m4d {

// An sRGB value in [0, 1] as linear light.
inline float SrgbToLinear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace m4d

#endif  // M4D_ENCODER_EXPORT_SRGB_H_
