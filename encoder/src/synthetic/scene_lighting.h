// SceneLighting: the synthetic scene's baked lighting (ambient + a directional sun + a point
// lamp, Lambertian, no shadows) and its evaluation on the CPU. The renderer's fragment
// shader evaluates the same formula, so initial points get the colours the images show.
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_LIGHTING_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_LIGHTING_H_

#include <glm/vec3.hpp>

#include "encoder/src/synthetic/synthetic_scene_options.h"

namespace m4d {

struct SceneLighting {
  glm::vec3 ambient;
  glm::vec3 sun_direction;  // unit, towards the sun
  glm::vec3 sun_colour;
  glm::vec3 lamp_position;
  glm::vec3 lamp_colour;  // at 1 m, falling off as 1 / (1 + d^2); also the shade's glow
};

// The factor all lights' strength takes at `frame`: 1 + light_flicker * u, u uniform in
// [-1, 1] drawn per frame; exactly 1 when flicker is off.
float LightFlickerGain(const SyntheticSceneOptions& options, int frame);

// Warm lamp light until options.background_change_frame, cold and brighter from it on; every
// light scaled by LightFlickerGain.
SceneLighting LightingAtFrame(const SyntheticSceneOptions& options, int frame);

// albedo * ((1 - emissive) * (ambient + sun + lamp) + emissive * lamp_colour), clamped to
// [0, 1]. `normal` need not be unit length.
glm::vec3 ShadeSurface(const SceneLighting& lighting, float emissive, const glm::vec3& position,
                       const glm::vec3& normal, const glm::vec3& albedo);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_LIGHTING_H_
