// Building blocks of the synthetic scene's meshes: quads, boxes, spheres and cylinders with
// outward normals and texture coordinates.
#ifndef M4D_ENCODER_SYNTHETIC_MESH_SHAPES_H_
#define M4D_ENCODER_SYNTHETIC_MESH_SHAPES_H_

#include "encoder/src/synthetic/triangle_mesh.h"

namespace m4d {

// How a box face or quad maps to texture coordinates: uv = uv_origin + uv_size * f, where f
// is the face position in [0, 1]^2, or in metres / metres_per_repeat when that is positive
// (so a texture keeps its scale on faces of any size).
struct UvMapping {
  glm::vec2 uv_origin{0.0f, 0.0f};
  glm::vec2 uv_size{1.0f, 1.0f};
  float metres_per_repeat = 0.0f;
};

// The parallelogram origin + s * edge_u + t * edge_v, s, t in [0, 1], facing
// cross(edge_u, edge_v); face coordinates (s, t).
TriangleMesh QuadMesh(const glm::vec3& origin, const glm::vec3& edge_u, const glm::vec3& edge_v,
                      const UvMapping& uv);

// An axis-aligned box of the given size centred on the origin, faces outward.
TriangleMesh BoxMesh(const glm::vec3& size, const UvMapping& uv);

// A sphere centred on the origin; u runs around the y axis from +z, v from the bottom pole.
TriangleMesh SphereMesh(float radius, int slices, int stacks);

// A cylinder (or a cone frustum) along +y from y = 0 to height, with caps; u runs around.
TriangleMesh CylinderMesh(float bottom_radius, float top_radius, float height, int slices);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_MESH_SHAPES_H_
