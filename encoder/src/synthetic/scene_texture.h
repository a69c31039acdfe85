// SceneTexture: an 8-bit RGB texture of the synthetic scene, and the bilinear, repeating
// lookup that matches what GL does with its base level (GL_LINEAR, GL_REPEAT), used to
// colour the initial points like the rendered surfaces.
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_TEXTURE_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_TEXTURE_H_

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace m4d {

struct SceneTexture {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // row-major, row 0 at v = 0 (GL's first row)
};

// A texture whose texel (x, y) is colour(u, v) at its centre, u = (x + 0.5) / width,
// v = (y + 0.5) / height, with colour components in [0, 1]. Rows are filled in parallel, so
// colour must be a pure function of its arguments.
SceneTexture MakeTexture(int width, int height,
                         const std::function<glm::vec3(float u, float v)>& colour);

// Bilinear lookup at (u, v), repeating with period 1 in both directions; values in [0, 1].
glm::vec3 SampleTexture(const SceneTexture& texture, float u, float v);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_TEXTURE_H_
