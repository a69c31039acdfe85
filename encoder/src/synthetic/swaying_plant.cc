#include "encoder/src/synthetic/swaying_plant.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "encoder/src/synthetic/mesh_shapes.h"

namespace m4d {
namespace {

const glm::vec3 kPotBase(-1.85f, 0.0f, -3.55f);
constexpr float kPotHeight = 0.32f;
constexpr float kFoliageHeight = 0.95f;  // from the rim to the top leaves
// Two incommensurate periods, in frames, so the sway does not repeat exactly.
constexpr float kSwayPeriod = 27.0f, kSecondPeriod = 11.0f;

}  // namespace

TriangleMesh PlantPotMesh() {
  TriangleMesh mesh;
  AppendMesh(CylinderMesh(0.12f, 0.16f, kPotHeight, 24), glm::translate(glm::mat4(1.0f), kPotBase),
             &mesh);
  return mesh;
}

TriangleMesh PlantFoliageMesh() {
  TriangleMesh mesh;
  const glm::mat4 identity(1.0f);
  AppendMesh(CylinderMesh(0.015f, 0.01f, 0.4f, 8), identity, &mesh);
  // Clumps of leaves, the top one reaching kFoliageHeight.
  const glm::vec4 clumps[] = {{0.0f, 0.45f, 0.0f, 0.24f},
                              {-0.12f, 0.62f, 0.06f, 0.18f},
                              {0.11f, 0.66f, -0.05f, 0.17f},
                              {0.0f, 0.79f, 0.0f, 0.16f}};
  for (const glm::vec4& c : clumps) {
    AppendMesh(SphereMesh(c.w, 20, 12), glm::translate(identity, glm::vec3(c)), &mesh);
  }
  return mesh;
}

glm::mat4 PlantFoliagePose(float sway, int frame) {
  const float t = 6.28318530718f * frame;
  // Tilt angles (radians) about z and x whose top displacement stays within `sway`.
  const float amplitude = sway / kFoliageHeight;
  const float about_z =
      amplitude * (0.7f * std::sin(t / kSwayPeriod) + 0.2f * std::sin(t / kSecondPeriod));
  const float about_x = 0.3f * amplitude * std::sin(t / kSwayPeriod + 1.3f);
  glm::mat4 pose = glm::translate(glm::mat4(1.0f), kPotBase + glm::vec3(0, kPotHeight, 0));
  pose = glm::rotate(pose, about_z, glm::vec3(0, 0, 1));
  return glm::rotate(pose, about_x, glm::vec3(1, 0, 0));
}

}  // namespace m4d
