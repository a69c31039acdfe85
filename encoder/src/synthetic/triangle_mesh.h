// TriangleMesh: indexed triangles with a normal and a texture coordinate per vertex, the
// geometry the synthetic scene renders and samples its initial points from.
#ifndef M4D_ENCODER_SYNTHETIC_TRIANGLE_MESH_H_
#define M4D_ENCODER_SYNTHETIC_TRIANGLE_MESH_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace m4d {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length
  std::vector<glm::vec2> uvs;      // texture coordinates; textures repeat
  std::vector<uint32_t> indices;   // 3 per triangle

  size_t vertex_count() const { return positions.size(); }
  size_t triangle_count() const { return indices.size() / 3; }

  // Adds a vertex and returns its index.
  uint32_t AddVertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv);
  void AddTriangle(uint32_t a, uint32_t b, uint32_t c);
};

// Adds `part` to *mesh with positions and normals moved by the rigid transform.
void AppendMesh(const TriangleMesh& part, const glm::mat4& transform, TriangleMesh* mesh);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_TRIANGLE_MESH_H_
