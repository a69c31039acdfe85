#include "encoder/src/synthetic/camera_rig.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace m4d {
namespace {

// The rig aims at this point; cameras stand on arcs of this radius about its vertical axis.
const glm::vec3 kTarget(0.0f, 1.0f, -1.8f);
constexpr float kArcRadius = 3.4f;
constexpr float kArcSpan = 0.62f;    // radians between the outermost columns
constexpr float kLowestRow = 0.95f;  // camera heights, metres
constexpr float kRowSpacing = 0.25f;
// A sparse rig's single arc stays this far inside the side walls (x = +-2.5).
constexpr float kSparseRigHalfWidth = 2.3f;

struct Slot {
  float column;  // arc angle fraction in [-0.5, 0.5]
  int row;
};

// Row-major slots: rows of `columns`, the last row centred when it is short. An odd number
// of rows, about sqrt(count) / 2, so that a middle row exists for camera 0.
std::vector<Slot> RigSlots(int count, int* rows) {
  *rows = 2 * static_cast<int>(std::lround(std::max(0.0, std::sqrt(count) / 2 - 1) / 2)) + 1;
  const int columns = (count + *rows - 1) / *rows;
  std::vector<Slot> slots;
  for (int r = 0; r < *rows; ++r) {
    const int in_row = std::min(columns, count - r * columns);
    for (int c = 0; c < in_row; ++c) {
      const float offset = 0.5f * (columns - in_row);
      const float column = columns > 1 ? (c + offset) / (columns - 1) - 0.5f : 0.0f;
      slots.push_back({column, r});
    }
  }
  return slots;
}

// The sparse rig: one row across the whole arc, at the middle row's height.
std::vector<Slot> SparseRigSlots(int count) {
  std::vector<Slot> slots;
  for (int c = 0; c < count; ++c) {
    slots.push_back({count > 1 ? static_cast<float>(c) / (count - 1) - 0.5f : 0.0f, 1});
  }
  return slots;
}

Camera LookingAt(const glm::vec3& centre, const SyntheticSceneOptions& options) {
  Camera camera;
  camera.width = options.width;
  camera.height = options.height;
  const float half_fov = 0.5f * options.horizontal_fov_degrees * 3.14159265f / 180.0f;
  camera.fx = camera.fy = 0.5f * options.width / std::tan(half_fov);
  camera.cx = 0.5f * options.width;
  camera.cy = 0.5f * options.height;
  // OpenCV axes: z forward, x right, y down (world y is up).
  const glm::vec3 forward = glm::normalize(kTarget - centre);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 down = glm::cross(forward, right);
  const glm::vec3 axes[3] = {right, down, forward};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) camera.rotation[3 * i + j] = axes[i][j];
    camera.translation[i] = -glm::dot(axes[i], centre);
  }
  camera.near_plane = 0.05f;
  return camera;
}

}  // namespace

std::vector<Camera> MakeCameraRig(const SyntheticSceneOptions& options) {
  const CaptureRealism& realism = options.realism;
  int rows = 1;
  std::vector<Slot> slots =
      realism.sparse_rig ? SparseRigSlots(options.cameras) : RigSlots(options.cameras, &rows);
  float span = kArcSpan, radius = kArcRadius;
  if (realism.sparse_rig) {
    span = realism.sparse_rig_arc_degrees * 3.14159265f / 180.0f;
    radius = std::min(kArcRadius, kSparseRigHalfWidth / std::sin(0.5f * span));
  }
  // The slot nearest the rig's centre becomes camera 0; the others keep their order.
  const float mid_row = realism.sparse_rig ? 1.0f : 0.5f * (rows - 1);
  const auto distance = [mid_row](const Slot& s) {
    return std::fabs(s.column) * 4 + std::fabs(s.row - mid_row);
  };
  const auto centre =
      std::min_element(slots.begin(), slots.end(),
                       [&](const Slot& a, const Slot& b) { return distance(a) < distance(b); });
  std::rotate(slots.begin(), centre, centre + 1);
  std::vector<Camera> cameras;
  for (const Slot& s : slots) {
    const float angle = span * s.column;
    const glm::vec3 position(kTarget.x + radius * std::sin(angle), kLowestRow + kRowSpacing * s.row,
                             kTarget.z + radius * std::cos(angle));
    cameras.push_back(LookingAt(position, options));
  }
  return cameras;
}

std::vector<std::string> CameraNames(int count) {
  int digits = 2;
  for (int n = count - 1; n >= 100; n /= 10) ++digits;
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) {
    const std::string number = std::to_string(i);
    names.push_back(
        "cam" + std::string(std::max(0, digits - static_cast<int>(number.size())), '0') + number);
  }
  return names;
}

}  // namespace m4d
