#include "encoder/src/synthetic/surface_point_sampler.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "encoder/src/synthetic/scene_lighting.h"
#include "encoder/src/synthetic/scene_random.h"

namespace m4d {
namespace {

struct Triangle {
  int object;
  uint32_t corner[3];
};

}  // namespace

PointCloud SampleSurfacePoints(const SceneContent& content, const SceneFrameState& state, int count,
                               uint64_t seed) {
  // World-space vertices of the visible objects, and every triangle's cumulative area.
  std::vector<std::vector<glm::vec3>> world(content.objects.size());
  std::vector<Triangle> triangles;
  std::vector<double> cumulative_area;
  double total = 0;
  for (size_t o = 0; o < content.objects.size(); ++o) {
    if (!state.visible[o]) continue;
    const TriangleMesh& mesh = content.objects[o].mesh;
    for (const glm::vec3& p : mesh.positions) {
      world[o].push_back(glm::vec3(state.model[o] * glm::vec4(p, 1.0f)));
    }
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      const uint32_t* c = &mesh.indices[3 * t];
      const glm::vec3 a = world[o][c[0]], b = world[o][c[1]], d = world[o][c[2]];
      total += 0.5 * glm::length(glm::cross(b - a, d - a));
      triangles.push_back({static_cast<int>(o), {c[0], c[1], c[2]}});
      cumulative_area.push_back(total);
    }
  }
  PointCloud cloud;
  if (triangles.empty() || count <= 0) return cloud;
  cloud.positions.reserve(3 * static_cast<size_t>(count));
  cloud.colors.reserve(3 * static_cast<size_t>(count));
  SceneRandom random(seed);
  for (int i = 0; i < count; ++i) {
    const double pick = random.Uniform() * total;
    const size_t t =
        std::min<size_t>(std::upper_bound(cumulative_area.begin(), cumulative_area.end(), pick) -
                             cumulative_area.begin(),
                         triangles.size() - 1);
    const Triangle& tri = triangles[t];
    const SceneObject& object = content.objects[tri.object];
    // Uniform over the triangle: barycentric weights from two uniforms.
    const float r = std::sqrt(random.Uniform()), s = random.Uniform();
    const float w[3] = {1 - r, r * (1 - s), r * s};
    glm::vec3 position(0.0f), normal(0.0f);
    glm::vec2 uv(0.0f);
    for (int k = 0; k < 3; ++k) {
      position += w[k] * world[tri.object][tri.corner[k]];
      normal += w[k] * object.mesh.normals[tri.corner[k]];
      uv += w[k] * object.mesh.uvs[tri.corner[k]];
    }
    normal = glm::mat3(state.model[tri.object]) * normal;
    const glm::vec3 albedo = SampleTexture(content.textures[object.texture], uv.x, uv.y);
    const glm::vec3 colour =
        ShadeSurface(state.lighting, object.emissive, position, normal, albedo);
    cloud.positions.insert(cloud.positions.end(), {position.x, position.y, position.z});
    cloud.colors.insert(cloud.colors.end(), {colour.r, colour.g, colour.b});
  }
  return cloud;
}

}  // namespace m4d
