#include "encoder/src/synthetic/triangle_mesh.h"

namespace m4d {

uint32_t TriangleMesh::AddVertex(const glm::vec3& position, const glm::vec3& normal,
                                 const glm::vec2& uv) {
  positions.push_back(position);
  normals.push_back(normal);
  uvs.push_back(uv);
  return static_cast<uint32_t>(positions.size() - 1);
}

void TriangleMesh::AddTriangle(uint32_t a, uint32_t b, uint32_t c) {
  indices.insert(indices.end(), {a, b, c});
}

void AppendMesh(const TriangleMesh& part, const glm::mat4& transform, TriangleMesh* mesh) {
  const uint32_t base = static_cast<uint32_t>(mesh->vertex_count());
  const glm::mat3 rotation(transform);
  for (size_t i = 0; i < part.vertex_count(); ++i) {
    mesh->AddVertex(glm::vec3(transform * glm::vec4(part.positions[i], 1.0f)),
                    rotation * part.normals[i], part.uvs[i]);
  }
  for (uint32_t index : part.indices) mesh->indices.push_back(base + index);
}

}  // namespace m4d
