#include "encoder/src/synthetic/articulated_figure.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "encoder/src/synthetic/mesh_shapes.h"

namespace m4d {
namespace {

constexpr float kTwoPi = 6.28318530718f;
// Frames per walking cycle, and per sway of the whole body along x. Paced like a person in a
// 30 fps capture: a limb's far end moves at most about 3 pixels a frame in the default 320x240
// views (a few pixels a frame at N3DV's resolution), the hips about one.
constexpr float kGaitPeriod = 40.0f;
constexpr float kSwayPeriod = 96.0f;

struct PartShape {
  const char* name;
  glm::vec3 size;  // box size; the head is a sphere of radius size.x
  FigureMaterial material;
};

constexpr PartShape kParts[kFigurePartCount] = {
    {"figure_torso", {0.38f, 0.55f, 0.22f}, FigureMaterial::kShirt},
    {"figure_head", {0.12f, 0.0f, 0.0f}, FigureMaterial::kSkin},
    {"figure_upper_arm_left", {0.10f, 0.30f, 0.10f}, FigureMaterial::kShirt},
    {"figure_forearm_left", {0.085f, 0.28f, 0.085f}, FigureMaterial::kSkin},
    {"figure_upper_arm_right", {0.10f, 0.30f, 0.10f}, FigureMaterial::kShirt},
    {"figure_forearm_right", {0.085f, 0.28f, 0.085f}, FigureMaterial::kSkin},
    {"figure_thigh_left", {0.14f, 0.42f, 0.14f}, FigureMaterial::kTrousers},
    {"figure_shin_left", {0.12f, 0.42f, 0.12f}, FigureMaterial::kTrousers},
    {"figure_thigh_right", {0.14f, 0.42f, 0.14f}, FigureMaterial::kTrousers},
    {"figure_shin_right", {0.12f, 0.42f, 0.12f}, FigureMaterial::kTrousers},
};

glm::mat4 Rotate(float angle, const glm::vec3& axis) {
  return glm::rotate(glm::mat4(1.0f), angle, axis);
}

glm::mat4 Translate(float x, float y, float z) {
  return glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z));
}

}  // namespace

const char* FigurePartName(int part) { return kParts[part].name; }

FigureMaterial FigurePartMaterial(int part) { return kParts[part].material; }

TriangleMesh FigurePartMesh(int part) {
  const PartShape& shape = kParts[part];
  if (part == kFigureHead) {
    TriangleMesh head;
    AppendMesh(SphereMesh(shape.size.x, 24, 16), Translate(0, shape.size.x, 0), &head);
    return head;
  }
  UvMapping uv;
  uv.metres_per_repeat = 0.3f;
  TriangleMesh mesh;
  // The torso stands on its joint (the hips); limbs hang from theirs.
  const float centre_y = part == kFigureTorso ? 0.5f * shape.size.y : -0.5f * shape.size.y;
  AppendMesh(BoxMesh(shape.size, uv), Translate(0, centre_y, 0), &mesh);
  return mesh;
}

std::array<glm::mat4, kFigurePartCount> FigurePose(int frame) {
  const float gait = kTwoPi * frame / kGaitPeriod, sway = kTwoPi * frame / kSwayPeriod;
  const glm::vec3 x(1, 0, 0), y(0, 1, 0);
  // The hips: 0.84 m up (two leg segments), swaying along x and turning about y.
  const glm::mat4 hips = Translate(-1.05f + 0.2f * std::sin(sway), 0.84f, -2.1f) *
                         Rotate(0.2f * std::sin(sway) + 0.3f, y);
  const float arm = 0.35f * std::sin(gait), leg = 0.3f * std::sin(gait);
  std::array<glm::mat4, kFigurePartCount> pose;
  pose[kFigureTorso] = hips * Rotate(0.05f * std::sin(2 * gait), x);
  const glm::mat4& torso = pose[kFigureTorso];
  pose[kFigureHead] = torso * Translate(0, 0.56f, 0) * Rotate(0.3f * std::sin(gait * 0.5f), y);
  pose[kFigureUpperArmLeft] =
      torso * Translate(-0.25f, 0.52f, 0) * Rotate(arm, x) * Rotate(-0.12f, glm::vec3(0, 0, 1));
  pose[kFigureForearmLeft] = pose[kFigureUpperArmLeft] * Translate(0, -0.30f, 0) *
                             Rotate(-0.5f - 0.4f * std::sin(gait + 1.0f), x);
  // The right arm waves: raised to the side, the forearm swinging.
  pose[kFigureUpperArmRight] = torso * Translate(0.25f, 0.52f, 0) *
                               Rotate(2.2f + 0.25f * std::sin(gait), glm::vec3(0, 0, 1));
  pose[kFigureForearmRight] = pose[kFigureUpperArmRight] * Translate(0, -0.30f, 0) *
                              Rotate(-0.4f * std::sin(2 * gait) - 0.3f, glm::vec3(0, 0, 1));
  pose[kFigureThighLeft] = hips * Translate(-0.1f, 0, 0) * Rotate(-leg, x);
  pose[kFigureShinLeft] = pose[kFigureThighLeft] * Translate(0, -0.42f, 0) *
                          Rotate(0.5f * std::max(0.0f, std::sin(gait)), x);
  pose[kFigureThighRight] = hips * Translate(0.1f, 0, 0) * Rotate(leg, x);
  pose[kFigureShinRight] = pose[kFigureThighRight] * Translate(0, -0.42f, 0) *
                           Rotate(0.5f * std::max(0.0f, -std::sin(gait)), x);
  return pose;
}

}  // namespace m4d
