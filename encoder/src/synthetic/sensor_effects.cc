#include "encoder/src/synthetic/sensor_effects.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/synthetic/scene_random.h"

namespace m4d {
namespace {

// Streams of the realism draws, apart from the content's.
uint64_t Stream(uint32_t seed, uint64_t stream) { return MixBits(seed * 6151ull + stream); }

// A standard normal from one 64-bit hash (Box-Muller on its two 24-bit halves).
float Normal(uint64_t hash) {
  const float u1 = (static_cast<float>(hash >> 40) + 1.0f) * (1.0f / 16777216.0f);  // (0, 1]
  const float u2 = static_cast<float>(hash & 0xFFFFFF) * (1.0f / 16777216.0f);
  return std::sqrt(-2.0f * std::log(u1)) * std::cos(6.28318530718f * u2);
}

}  // namespace

glm::vec3 CameraColourGain(const SyntheticSceneOptions& options, int camera) {
  const CaptureRealism& r = options.realism;
  SceneRandom random(Stream(options.seed, 1) + static_cast<uint64_t>(camera));
  const float exposure = 1.0f + r.exposure_spread * random.Uniform(-1.0f, 1.0f);
  glm::vec3 gain;
  for (int ch = 0; ch < 3; ++ch) {
    gain[ch] = exposure * (1.0f + r.white_balance_spread * random.Uniform(-1.0f, 1.0f));
  }
  return gain;
}

bool HasSensorEffects(const CaptureRealism& realism) {
  return realism.noise_sigma > 0.0f || realism.exposure_spread > 0.0f ||
         realism.white_balance_spread > 0.0f;
}

void ApplySensorEffects(const SyntheticSceneOptions& options, int frame, int camera,
                        const std::vector<float>& levels, std::vector<uint8_t>* rgb) {
  const glm::vec3 gain = CameraColourGain(options, camera);
  const float sigma = options.realism.noise_sigma;
  const uint64_t view = MixBits(Stream(options.seed, 2) +
                                static_cast<uint64_t>(frame) * kMaxSyntheticCameras + camera);
  rgb->resize(levels.size());
  for (size_t i = 0; i < levels.size(); ++i) {
    float value = levels[i] * gain[i % 3];
    if (sigma > 0.0f) value += sigma * Normal(MixBits(view ^ MixBits(i)));
    (*rgb)[i] = static_cast<uint8_t>(std::clamp(std::lround(value), 0l, 255l));
  }
}

}  // namespace m4d
