#include "encoder/src/synthetic/mesh_shapes.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace m4d {
namespace {

constexpr float kPi = 3.14159265359f;

glm::vec2 FaceUv(const UvMapping& uv, float s, float t, float length_u, float length_v) {
  glm::vec2 f(s, t);
  if (uv.metres_per_repeat > 0) f *= glm::vec2(length_u, length_v) / uv.metres_per_repeat;
  return uv.uv_origin + uv.uv_size * f;
}

void AddQuad(const glm::vec3& origin, const glm::vec3& edge_u, const glm::vec3& edge_v,
             const UvMapping& uv, TriangleMesh* mesh) {
  const glm::vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
  const float lu = glm::length(edge_u), lv = glm::length(edge_v);
  uint32_t corner[4];
  for (int i = 0; i < 4; ++i) {
    const float s = static_cast<float>(i & 1), t = static_cast<float>(i >> 1);
    corner[i] = mesh->AddVertex(origin + s * edge_u + t * edge_v, normal, FaceUv(uv, s, t, lu, lv));
  }
  mesh->AddTriangle(corner[0], corner[1], corner[3]);
  mesh->AddTriangle(corner[0], corner[3], corner[2]);
}

}  // namespace

TriangleMesh QuadMesh(const glm::vec3& origin, const glm::vec3& edge_u, const glm::vec3& edge_v,
                      const UvMapping& uv) {
  TriangleMesh mesh;
  AddQuad(origin, edge_u, edge_v, uv, &mesh);
  return mesh;
}

TriangleMesh BoxMesh(const glm::vec3& size, const UvMapping& uv) {
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 x(size.x, 0, 0), y(0, size.y, 0), z(0, 0, size.z);
  TriangleMesh mesh;
  AddQuad(glm::vec3(-h.x, -h.y, h.z), x, y, uv, &mesh);   // front (+z)
  AddQuad(glm::vec3(h.x, -h.y, -h.z), -x, y, uv, &mesh);  // back (-z)
  AddQuad(glm::vec3(h.x, -h.y, h.z), -z, y, uv, &mesh);   // right (+x)
  AddQuad(glm::vec3(-h.x, -h.y, -h.z), z, y, uv, &mesh);  // left (-x)
  AddQuad(glm::vec3(-h.x, h.y, h.z), x, -z, uv, &mesh);   // top (+y)
  AddQuad(glm::vec3(-h.x, -h.y, -h.z), x, z, uv, &mesh);  // bottom (-y)
  return mesh;
}

TriangleMesh SphereMesh(float radius, int slices, int stacks) {
  TriangleMesh mesh;
  for (int j = 0; j <= stacks; ++j) {
    const float v = static_cast<float>(j) / stacks, theta = kPi * (1.0f - v);
    for (int i = 0; i <= slices; ++i) {
      const float u = static_cast<float>(i) / slices, phi = 2 * kPi * u;
      const glm::vec3 n(std::sin(phi) * std::sin(theta), std::cos(theta),
                        std::cos(phi) * std::sin(theta));
      mesh.AddVertex(radius * n, n, glm::vec2(u, v));
    }
  }
  const uint32_t row = static_cast<uint32_t>(slices + 1);
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      mesh.AddTriangle(a, b, d);
      mesh.AddTriangle(a, d, c);
    }
  }
  return mesh;
}

TriangleMesh CylinderMesh(float bottom_radius, float top_radius, float height, int slices) {
  TriangleMesh mesh;
  // The side's normal leans by the slope of a frustum.
  const float slope = (bottom_radius - top_radius) / height;
  for (int i = 0; i <= slices; ++i) {
    const float u = static_cast<float>(i) / slices, phi = 2 * kPi * u;
    const glm::vec3 radial(std::sin(phi), 0, std::cos(phi));
    const glm::vec3 n = glm::normalize(radial + glm::vec3(0, slope, 0));
    mesh.AddVertex(bottom_radius * radial, n, glm::vec2(u, 0));
    mesh.AddVertex(top_radius * radial + glm::vec3(0, height, 0), n, glm::vec2(u, 1));
  }
  for (int i = 0; i < slices; ++i) {
    const uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
    mesh.AddTriangle(a, c, d);
    mesh.AddTriangle(a, d, b);
  }
  for (int cap = 0; cap < 2; ++cap) {
    const float y = cap ? height : 0.0f, r = cap ? top_radius : bottom_radius;
    const glm::vec3 n(0, cap ? 1.0f : -1.0f, 0);
    const uint32_t centre = mesh.AddVertex(glm::vec3(0, y, 0), n, glm::vec2(0.5f, 0.5f));
    for (int i = 0; i < slices; ++i) {
      const float p0 = 2 * kPi * i / slices, p1 = 2 * kPi * (i + 1) / slices;
      const uint32_t a = mesh.AddVertex(glm::vec3(r * std::sin(p0), y, r * std::cos(p0)), n,
                                        glm::vec2(0.5f + 0.5f * std::sin(p0), 0.5f));
      const uint32_t b = mesh.AddVertex(glm::vec3(r * std::sin(p1), y, r * std::cos(p1)), n,
                                        glm::vec2(0.5f + 0.5f * std::sin(p1), 0.5f));
      if (cap) {
        mesh.AddTriangle(centre, a, b);
      } else {
        mesh.AddTriangle(centre, b, a);
      }
    }
  }
  return mesh;
}

}  // namespace m4d
