#include "sdk/src/render/splat_geometry.h"

#include <cmath>

namespace m4d {
namespace {

bool Finite3(const float* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void QuaternionToRotation(float w, float x, float y, float z, float r[9]) {
  r[0] = 1.0f - 2.0f * (y * y + z * z);
  r[1] = 2.0f * (x * y - w * z);
  r[2] = 2.0f * (x * z + w * y);
  r[3] = 2.0f * (x * y + w * z);
  r[4] = 1.0f - 2.0f * (x * x + z * z);
  r[5] = 2.0f * (y * z - w * x);
  r[6] = 2.0f * (x * z - w * y);
  r[7] = 2.0f * (y * z + w * x);
  r[8] = 1.0f - 2.0f * (x * x + y * y);
}

// M M^T with M = R diag(scale): upper triangle xx, xy, xz, yy, yz, zz.
void Covariance3D(const float r[9], const float scale[3], float cov[6]) {
  float m[9];
  for (int i = 0; i < 9; ++i) m[i] = r[i] * scale[i % 3];
  const int rows[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  for (int k = 0; k < 6; ++k) {
    const float* a = m + 3 * rows[k][0];
    const float* b = m + 3 * rows[k][1];
    cov[k] = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }
}

float Clamp(float v, const float limit[2], bool* clamped) {
  *clamped = v < limit[0] || v > limit[1];
  return v < limit[0] ? limit[0] : (v > limit[1] ? limit[1] : v);
}

// J W for the camera-space point t.
void ProjectionJacobian(const ProjectionConstants& pc, const float t[3], SplatGeometry* g) {
  const float inv_z = 1.0f / t[2];
  const float xz = Clamp(t[0] * inv_z, pc.limit_x, &g->clamped_x);
  const float yz = Clamp(t[1] * inv_z, pc.limit_y, &g->clamped_y);
  const float j00 = pc.fx * inv_z, j02 = -pc.fx * xz * inv_z;
  const float j11 = pc.fy * inv_z, j12 = -pc.fy * yz * inv_z;
  const float* w = pc.rotation;
  for (int k = 0; k < 3; ++k) {
    g->jw[k] = j00 * w[k] + j02 * w[6 + k];
    g->jw[3 + k] = j11 * w[3 + k] + j12 * w[6 + k];
  }
}

// (J W) cov3 (J W)^T, dilated.
void ProjectCovariance(SplatGeometry* g) {
  const float* c = g->cov3;
  const float full[9] = {c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5]};
  float m[6];  // J W cov3
  for (int i = 0; i < 2; ++i) {
    const float* row = g->jw + 3 * i;
    for (int k = 0; k < 3; ++k) {
      m[3 * i + k] = row[0] * full[k] + row[1] * full[3 + k] + row[2] * full[6 + k];
    }
  }
  const float* j = g->jw;
  g->cov2[0] = m[0] * j[0] + m[1] * j[1] + m[2] * j[2] + kCovarianceDilation;
  g->cov2[1] = m[0] * j[3] + m[1] * j[4] + m[2] * j[5];
  g->cov2[2] = m[3] * j[3] + m[4] * j[4] + m[5] * j[5] + kCovarianceDilation;
}

}  // namespace

bool ComputeSplatGeometry(const ProjectionConstants& pc, const float p[3], const float log_scale[3],
                          const float q[4], SplatGeometry* g) {
  const float* r = pc.rotation;
  for (int a = 0; a < 3; ++a) {
    g->view[a] = r[3 * a] * p[0] + r[3 * a + 1] * p[1] + r[3 * a + 2] * p[2] + pc.translation[a];
  }
  const float q_norm2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  for (int a = 0; a < 3; ++a) g->scale[a] = std::exp(log_scale[a]);
  if (!(g->view[2] > pc.near_plane) || !Finite3(g->view) || !(q_norm2 > 0.0f) ||
      !std::isfinite(q_norm2) || !Finite3(g->scale)) {
    return false;
  }
  const float inv_q = 1.0f / std::sqrt(q_norm2);
  QuaternionToRotation(q[0] * inv_q, q[1] * inv_q, q[2] * inv_q, q[3] * inv_q, g->rotation);
  Covariance3D(g->rotation, g->scale, g->cov3);
  ProjectionJacobian(pc, g->view, g);
  ProjectCovariance(g);
  return true;
}

}  // namespace m4d
