#include "encoder/src/synthetic/scene_animation.h"

#include <glm/gtc/matrix_transform.hpp>

#include "encoder/src/synthetic/articulated_figure.h"
#include "encoder/src/synthetic/swaying_plant.h"

namespace m4d {
namespace {

// The cube turns 3 degrees a frame about a tilted axis.
constexpr float kCubeTurnPerFrame = 0.0524f;

}  // namespace

glm::vec3 EmergentObjectCentre() { return glm::vec3(0.15f, 0.16f, -0.9f); }

glm::vec3 RotatingObjectCentre() { return glm::vec3(0.75f, 1.085f, -1.9f); }

SceneFrameState SceneStateAt(const SceneContent& content, const SyntheticSceneOptions& options,
                             int frame) {
  SceneFrameState state;
  state.lighting = LightingAtFrame(options, frame);
  const auto figure = FigurePose(frame);
  const glm::mat4 identity(1.0f);
  const glm::mat4 cube =
      glm::rotate(glm::translate(identity, RotatingObjectCentre()), kCubeTurnPerFrame * frame,
                  glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
  const glm::mat4 ball =
      glm::rotate(glm::translate(identity, EmergentObjectCentre()), 0.6f, glm::vec3(0, 1, 0));
  for (const SceneObject& object : content.objects) {
    glm::mat4 model = identity;
    bool visible = true;
    switch (object.motion) {
      case ObjectMotion::kStatic:
        break;
      case ObjectMotion::kFigurePart:
        model = figure[object.figure_part];
        break;
      case ObjectMotion::kRotating:
        model = cube;
        break;
      case ObjectMotion::kEmergent:
        model = ball;
        visible = frame >= EmergentFrame(options);
        break;
      case ObjectMotion::kSwaying:
        model = PlantFoliagePose(options.realism.background_sway, frame);
        break;
    }
    state.model.push_back(model);
    state.visible.push_back(visible ? 1 : 0);
  }
  return state;
}

}  // namespace m4d
