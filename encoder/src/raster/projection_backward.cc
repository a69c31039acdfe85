#include "encoder/src/raster/projection_backward.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/raster/sh_backward.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/render/sh_evaluation.h"
#include "sdk/src/render/splat_geometry.h"

namespace m4d {
namespace {

float Dot3(const float* a, const float* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// SH: gradients of the coefficients, and adds the view-direction term to dL/dposition.
void BackpropagateColour(const ProjectionConstants& pc, const M4dGaussians& layer, int degree,
                         size_t i, const float dl_dcolor[3], float* dl_dsh, float dl_dposition[3]) {
  const int stored = ShCoefficients(layer.sh_degree), active = ShCoefficients(degree);
  const float* sh = layer.sh + 3 * static_cast<size_t>(stored) * i;
  const float* p = layer.positions + 3 * i;
  float dir[3];
  for (int a = 0; a < 3; ++a) dir[a] = p[a] - pc.centre[a];
  const float len = std::sqrt(Dot3(dir, dir));
  for (float& d : dir) d /= len;
  float basis[kMaxShCoefficients], grad[kMaxShCoefficients][3];
  ShBasis(degree, dir[0], dir[1], dir[2], basis);
  ShBasisGradient(degree, dir[0], dir[1], dir[2], grad);
  float dl_ddir[3] = {0, 0, 0};
  for (int k = 0; k < active; ++k) {
    float along = 0;  // dL/d basis[k]
    for (int c = 0; c < 3; ++c) {
      dl_dsh[3 * k + c] = basis[k] * dl_dcolor[c];
      along += sh[3 * k + c] * dl_dcolor[c];
    }
    for (int a = 0; a < 3; ++a) dl_ddir[a] += along * grad[k][a];
  }
  std::fill(dl_dsh + 3 * active, dl_dsh + 3 * stored, 0.0f);
  // dir = d / |d|: remove the radial component, divide by the length.
  const float radial = Dot3(dir, dl_ddir);
  for (int a = 0; a < 3; ++a) dl_dposition[a] += (dl_ddir[a] - radial * dir[a]) / len;
}

// From dL/d(conic) to dL/d(dilated 2D covariance a, b, c), conic = (c, -b, a) / det.
void ConicToCovariance(const float cov[3], const float dl_dconic[3], float dl_dcov[3]) {
  const float a = cov[0], b = cov[1], c = cov[2];
  const float inv = 1.0f / (a * c - b * b), inv2 = inv * inv;
  const float ga = dl_dconic[0], gb = dl_dconic[1], gc = dl_dconic[2];
  dl_dcov[0] = ga * (-c * c * inv2) + gb * (b * c * inv2) + gc * (inv - a * c * inv2);
  dl_dcov[1] = ga * (2 * b * c * inv2) + gb * (-inv - 2 * b * b * inv2) + gc * (2 * a * b * inv2);
  dl_dcov[2] = ga * (inv - a * c * inv2) + gb * (a * b * inv2) + gc * (-a * a * inv2);
}

// dL/d(camera-space mean) from dL/d(J W) (2x3) and dL/d(u, v).
void BackpropagateJacobian(const ProjectionConstants& pc, const SplatGeometry& geo,
                           const float dl_djw[6], const float dl_dmean[2], float dl_dt[3]) {
  const float* w = pc.rotation;
  const float* t = geo.view;
  const float inv_z = 1.0f / t[2], inv_z2 = inv_z * inv_z;
  const float dj00 = Dot3(dl_djw, w), dj02 = Dot3(dl_djw, w + 6);
  const float dj11 = Dot3(dl_djw + 3, w + 3), dj12 = Dot3(dl_djw + 3, w + 6);
  const float raw_x = t[0] * inv_z, raw_y = t[1] * inv_z;
  // J02 = -fx xz / z with xz = t.x / z, or a constant limit when clamped; likewise J12.
  const float xz = geo.clamped_x ? (raw_x < pc.limit_x[0] ? pc.limit_x[0] : pc.limit_x[1]) : raw_x;
  const float yz = geo.clamped_y ? (raw_y < pc.limit_y[0] ? pc.limit_y[0] : pc.limit_y[1]) : raw_y;
  const float dl_dxz = geo.clamped_x ? 0.0f : -dj02 * pc.fx * inv_z;
  const float dl_dyz = geo.clamped_y ? 0.0f : -dj12 * pc.fy * inv_z;
  dl_dt[0] = dl_dxz * inv_z;
  dl_dt[1] = dl_dyz * inv_z;
  dl_dt[2] = (-dj00 * pc.fx - dj11 * pc.fy + dj02 * pc.fx * xz + dj12 * pc.fy * yz) * inv_z2 -
             (dl_dxz * raw_x + dl_dyz * raw_y) * inv_z;
  // u = fx t.x / z + cx, v = fy t.y / z + cy.
  dl_dt[0] += dl_dmean[0] * pc.fx * inv_z;
  dl_dt[1] += dl_dmean[1] * pc.fy * inv_z;
  dl_dt[2] -= (dl_dmean[0] * pc.fx * t[0] + dl_dmean[1] * pc.fy * t[1]) * inv_z2;
}

// dL/d(unnormalised quaternion q) from dL/d(rotation matrix of q / |q|).
void BackpropagateRotation(const float q[4], const float dl_dr[9], float dl_dq[4]) {
  const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const float w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
  const float* g = dl_dr;
  const float gu[4] = {2 * (-z * g[1] + y * g[2] + z * g[3] - x * g[5] - y * g[6] + x * g[7]),
                       2 * (y * g[1] + z * g[2] + y * g[3] - 2 * x * g[4] - w * g[5] + z * g[6] +
                            w * g[7] - 2 * x * g[8]),
                       2 * (-2 * y * g[0] + x * g[1] + w * g[2] + x * g[3] + z * g[5] - w * g[6] +
                            z * g[7] - 2 * y * g[8]),
                       2 * (-2 * z * g[0] - w * g[1] + x * g[2] + w * g[3] - 2 * z * g[4] +
                            y * g[5] + x * g[6] + y * g[7])};
  const float unit[4] = {w, x, y, z};
  const float along = gu[0] * w + gu[1] * x + gu[2] * y + gu[3] * z;
  for (int k = 0; k < 4; ++k) dl_dq[k] = (gu[k] - along * unit[k]) / norm;
}

}  // namespace

void BackpropagateProjection(const ProjectionConstants& pc, const M4dGaussians& layer,
                             int sh_degree, size_t i, const SplatGradient& grad,
                             uint8_t color_clamped, const LayerGradients& out) {
  const float* p = layer.positions + 3 * i;
  const float* q = layer.rotations + 4 * i;
  const float* log_scale = layer.log_scales + 3 * i;
  float* dl_dp = out.positions + 3 * i;
  const int degree = std::min(sh_degree, static_cast<int>(layer.sh_degree));

  // Opacity.
  const float opacity = 1.0f / (1.0f + std::exp(-layer.opacity_logits[i]));
  out.opacity_logits[i] = grad.opacity * opacity * (1.0f - opacity);

  // Colour.
  float dl_dcolor[3];
  for (int c = 0; c < 3; ++c) dl_dcolor[c] = ((color_clamped >> c) & 1) ? 0.0f : grad.color[c];
  for (int a = 0; a < 3; ++a) dl_dp[a] = 0.0f;
  const size_t sh_stride = 3 * static_cast<size_t>(ShCoefficients(layer.sh_degree));
  BackpropagateColour(pc, layer, degree, i, dl_dcolor, out.sh + sh_stride * i, dl_dp);

  // The forward geometry (visible Gaussians always have one).
  SplatGeometry geo;
  ComputeSplatGeometry(pc, p, log_scale, q, &geo);

  // cov2 = (J W) cov3 (J W)^T.
  float dl_dcov2[3];
  ConicToCovariance(geo.cov2, grad.conic, dl_dcov2);
  const float *t0 = geo.jw, *t1 = geo.jw + 3;
  const float* c = geo.cov3;
  const float cov3[9] = {c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5]};
  float s_t0[3], s_t1[3];  // cov3 T0^T, cov3 T1^T
  for (int a = 0; a < 3; ++a) {
    s_t0[a] = Dot3(cov3 + 3 * a, t0);
    s_t1[a] = Dot3(cov3 + 3 * a, t1);
  }
  float dl_djw[6];
  for (int a = 0; a < 3; ++a) {
    dl_djw[a] = 2 * dl_dcov2[0] * s_t0[a] + dl_dcov2[1] * s_t1[a];
    dl_djw[3 + a] = dl_dcov2[1] * s_t0[a] + 2 * dl_dcov2[2] * s_t1[a];
  }
  float dl_dt[3];
  BackpropagateJacobian(pc, geo, dl_djw, grad.mean, dl_dt);
  for (int a = 0; a < 3; ++a) {
    dl_dp[a] +=
        pc.rotation[a] * dl_dt[0] + pc.rotation[3 + a] * dl_dt[1] + pc.rotation[6 + a] * dl_dt[2];
  }

  // cov3 = M M^T with M = R diag(scale): dL/dM = (G + G^T) M, G = dL/dcov3.
  float g_sym[9];
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      g_sym[3 * a + b] = 2 * dl_dcov2[0] * t0[a] * t0[b] +
                         dl_dcov2[1] * (t0[a] * t1[b] + t1[a] * t0[b]) +
                         2 * dl_dcov2[2] * t1[a] * t1[b];
    }
  }
  const float* rot = geo.rotation;
  const float* scale = geo.scale;
  float dl_drot[9];
  for (int b = 0; b < 3; ++b) {
    float dl_dscale = 0;
    for (int a = 0; a < 3; ++a) {
      // dL/dM[a][b] = sum_k g_sym[a][k] M[k][b], M[k][b] = rot[k][b] scale[b].
      const float dl_dm =
          (g_sym[3 * a] * rot[b] + g_sym[3 * a + 1] * rot[3 + b] + g_sym[3 * a + 2] * rot[6 + b]) *
          scale[b];
      dl_drot[3 * a + b] = dl_dm * scale[b];
      dl_dscale += dl_dm * rot[3 * a + b];
    }
    out.log_scales[3 * i + b] = dl_dscale * scale[b];
  }
  BackpropagateRotation(q, dl_drot, out.rotations + 4 * i);
}

void ZeroGradients(const M4dGaussians& layer, size_t i, const LayerGradients& out) {
  std::fill(out.positions + 3 * i, out.positions + 3 * i + 3, 0.0f);
  std::fill(out.log_scales + 3 * i, out.log_scales + 3 * i + 3, 0.0f);
  std::fill(out.rotations + 4 * i, out.rotations + 4 * i + 4, 0.0f);
  out.opacity_logits[i] = 0.0f;
  const size_t stride = 3 * static_cast<size_t>(ShCoefficients(layer.sh_degree));
  std::fill(out.sh + stride * i, out.sh + stride * (i + 1), 0.0f);
}

}  // namespace m4d
