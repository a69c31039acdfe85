// Conversions between float samples and the 8-bit samples of image files.
#ifndef M4D_ENCODER_IMAGE_IO_BYTE_SAMPLES_H_
#define M4D_ENCODER_IMAGE_IO_BYTE_SAMPLES_H_

#include <cstdint>

namespace m4d {

// round(clamp(v, 0, 1) * 255), halves rounding up; NaN gives 0.
inline uint8_t FloatToByte(float v) {
  const float clamped = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return static_cast<uint8_t>(clamped * 255.0f + 0.5f);
}

// FloatToByte(ByteToFloat(b)) == b for every byte: 8-bit files round-trip exactly.
inline float ByteToFloat(uint8_t b) { return static_cast<float>(b) / 255.0f; }

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_IO_BYTE_SAMPLES_H_
