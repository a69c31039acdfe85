// SceneFrameState: where every object of the synthetic scene is at a frame, whether it is
// there at all, and the lighting: the articulated figure's pose, the cube's spin, the ball
// from the emergent frame on, the plant's sway, and the lamp's change and flicker.
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_ANIMATION_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_ANIMATION_H_

#include <vector>

#include <glm/mat4x4.hpp>

#include "encoder/src/synthetic/scene_content.h"
#include "encoder/src/synthetic/scene_lighting.h"
#include "encoder/src/synthetic/synthetic_scene_options.h"

namespace m4d {

struct SceneFrameState {
  std::vector<glm::mat4> model;  // object-to-world, one per SceneContent::objects entry
  std::vector<char> visible;     // 0 for an object not in the scene at this frame
  SceneLighting lighting;
};

SceneFrameState SceneStateAt(const SceneContent& content, const SyntheticSceneOptions& options,
                             int frame);

// Where the emergent ball rests, and the cube's centre: for scene.json and tests.
glm::vec3 EmergentObjectCentre();
glm::vec3 RotatingObjectCentre();

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_ANIMATION_H_
