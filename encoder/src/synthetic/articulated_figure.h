// The articulated figure of the synthetic scene: a person-like chain of boxes and a sphere
// (torso, head, upper and lower arms and legs) whose joints swing over time in a walking
// gait while the body sways along x and turns a little. Each part's mesh is in its own
// joint frame; FigurePose gives the part-to-world transforms at a frame.
#ifndef M4D_ENCODER_SYNTHETIC_ARTICULATED_FIGURE_H_
#define M4D_ENCODER_SYNTHETIC_ARTICULATED_FIGURE_H_

#include <array>

#include <glm/mat4x4.hpp>

#include "encoder/src/synthetic/triangle_mesh.h"

namespace m4d {

enum FigurePart {
  kFigureTorso,
  kFigureHead,
  kFigureUpperArmLeft,
  kFigureForearmLeft,
  kFigureUpperArmRight,
  kFigureForearmRight,
  kFigureThighLeft,
  kFigureShinLeft,
  kFigureThighRight,
  kFigureShinRight,
  kFigurePartCount
};

enum class FigureMaterial { kSkin, kShirt, kTrousers };

const char* FigurePartName(int part);
FigureMaterial FigurePartMaterial(int part);

// The part's mesh in its joint frame (limbs hang down -y from the joint at the origin).
TriangleMesh FigurePartMesh(int part);

// Part-to-world transforms at `frame`.
std::array<glm::mat4, kFigurePartCount> FigurePose(int frame);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_ARTICULATED_FIGURE_H_
