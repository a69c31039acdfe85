#include "encoder/src/synthetic/scene_lighting.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "encoder/src/synthetic/scene_random.h"

namespace m4d {

float LightFlickerGain(const SyntheticSceneOptions& options, int frame) {
  const float flicker = options.realism.light_flicker;
  if (flicker == 0.0f) return 1.0f;
  SceneRandom random(MixBits(options.seed * 6151ull + 3) + static_cast<uint64_t>(frame));
  return 1.0f + flicker * random.Uniform(-1.0f, 1.0f);
}

SceneLighting LightingAtFrame(const SyntheticSceneOptions& options, int frame) {
  SceneLighting l;
  l.ambient = glm::vec3(0.42f, 0.42f, 0.44f);
  l.sun_direction = glm::normalize(glm::vec3(0.35f, 0.8f, 0.5f));
  l.sun_colour = glm::vec3(0.45f, 0.44f, 0.40f);
  l.lamp_position = glm::vec3(1.9f, 1.62f, -2.6f);
  const bool changed =
      options.background_change_frame >= 0 && frame >= options.background_change_frame;
  l.lamp_colour = changed ? glm::vec3(0.45f, 0.75f, 1.6f) : glm::vec3(1.3f, 0.95f, 0.55f);
  const float flicker = LightFlickerGain(options, frame);
  l.ambient *= flicker;
  l.sun_colour *= flicker;
  l.lamp_colour *= flicker;
  return l;
}

glm::vec3 ShadeSurface(const SceneLighting& l, float emissive, const glm::vec3& position,
                       const glm::vec3& normal, const glm::vec3& albedo) {
  const glm::vec3 n = glm::normalize(normal);
  const glm::vec3 to_lamp = l.lamp_position - position;
  const float d2 = glm::dot(to_lamp, to_lamp);
  const float lamp = std::max(glm::dot(n, to_lamp) / std::sqrt(d2), 0.0f) / (1.0f + d2);
  const glm::vec3 light = l.ambient + l.sun_colour * std::max(glm::dot(n, l.sun_direction), 0.0f) +
                          l.lamp_colour * lamp;
  const glm::vec3 lit = albedo * ((1.0f - emissive) * light + emissive * l.lamp_colour);
  return glm::clamp(lit, 0.0f, 1.0f);
}

}  // namespace m4d
