#include "sdk/src/render/splat_projection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/render/sh_evaluation.h"
#include "sdk/src/render/splat_alpha.h"
#include "sdk/src/render/splat_geometry.h"

namespace m4d {
namespace {

void Cull(size_t g, ProjectedSplats* out) {
  out->mean_x[g] = out->mean_y[g] = out->depth[g] = out->radius[g] = 0.0f;
  out->extent_x[g] = out->extent_y[g] = 0.0f;
  out->conic_a[g] = out->conic_b[g] = out->conic_c[g] = out->opacity[g] = 0.0f;
  for (int c = 0; c < 3; ++c) out->color[c][g] = 0.0f;
  out->color_clamped[g] = 0;
  for (int k = 0; k < 4; ++k) out->tile_rect[4 * g + k] = 0;
}

// Tiles covered by the pixels whose centre may lie within `extent` of `mean` along one axis
// (one pixel of slack for rounding), clamped to [0, tiles). False when none.
bool TileSpan(float mean, float extent, int tiles, uint16_t* first, uint16_t* last) {
  const float lo = std::floor((mean - extent - 1.0f) / kTileSize);
  const float hi = std::floor((mean + extent) / kTileSize);
  if (!(hi >= 0.0f) || !(lo <= static_cast<float>(tiles - 1))) return false;
  *first = static_cast<uint16_t>(std::max(lo, 0.0f));
  *last = static_cast<uint16_t>(std::min(hi, static_cast<float>(tiles - 1)));
  return true;
}

bool Finite3(const float* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// The colour of Gaussian i, or false when it is not finite.
bool SplatColour(const ProjectionConstants& pc, const M4dGaussians& layer, int degree, size_t i,
                 float colour[3], uint8_t* clamped) {
  const float* p = layer.positions + 3 * i;
  float dir[3];
  for (int a = 0; a < 3; ++a) dir[a] = p[a] - pc.centre[a];
  const float inv_len = 1.0f / std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  float basis[kMaxShCoefficients];
  ShBasis(degree, dir[0] * inv_len, dir[1] * inv_len, dir[2] * inv_len, basis);
  const size_t stride = 3 * static_cast<size_t>(ShCoefficients(layer.sh_degree));
  ShColour(basis, ShCoefficients(degree), layer.sh + stride * i, colour);
  *clamped = 0;
  for (int c = 0; c < 3; ++c) {
    if (colour[c] < 0.0f) {
      colour[c] = 0.0f;
      *clamped |= static_cast<uint8_t>(1u << c);
    }
  }
  return Finite3(colour);
}

void ProjectOne(const ProjectionConstants& pc, const M4dGaussians& layer, int degree, size_t i,
                size_t g, ProjectedSplats* out) {
  const float opacity = 1.0f / (1.0f + std::exp(-layer.opacity_logits[i]));
  SplatGeometry geo;
  if (!(opacity >= kMinAlpha) ||
      !ComputeSplatGeometry(pc, layer.positions + 3 * i, layer.log_scales + 3 * i,
                            layer.rotations + 4 * i, &geo)) {
    return Cull(g, out);
  }
  const float a = geo.cov2[0], b = geo.cov2[1], c = geo.cov2[2];
  const float det = a * c - b * b;
  if (!(det > 0.0f) || !std::isfinite(det)) return Cull(g, out);
  const float mid = 0.5f * (a + c);
  const float lambda = mid + std::sqrt(std::max(0.1f, mid * mid - det));
  const float radius = std::ceil(3.0f * std::sqrt(lambda));
  const float k2 = 2.0f * std::log(255.0f * opacity) + 0.05f;
  const float extent_x = std::min(radius, std::sqrt(k2 * a));
  const float extent_y = std::min(radius, std::sqrt(k2 * c));
  const float inv_z = 1.0f / geo.view[2];
  const float u = pc.fx * geo.view[0] * inv_z + pc.cx;
  const float v = pc.fy * geo.view[1] * inv_z + pc.cy;
  uint16_t rect[4];
  if (!std::isfinite(radius) || !TileSpan(u, extent_x, pc.tiles_x, &rect[0], &rect[2]) ||
      !TileSpan(v, extent_y, pc.tiles_y, &rect[1], &rect[3])) {
    return Cull(g, out);
  }
  float colour[3];
  uint8_t clamped;
  if (!SplatColour(pc, layer, degree, i, colour, &clamped)) return Cull(g, out);
  const float inv_det = 1.0f / det;
  out->mean_x[g] = u;
  out->mean_y[g] = v;
  out->depth[g] = geo.view[2];
  out->radius[g] = radius;
  out->extent_x[g] = extent_x;
  out->extent_y[g] = extent_y;
  out->conic_a[g] = c * inv_det;
  out->conic_b[g] = -b * inv_det;
  out->conic_c[g] = a * inv_det;
  out->opacity[g] = opacity;
  for (int k = 0; k < 3; ++k) out->color[k][g] = colour[k];
  out->color_clamped[g] = clamped;
  for (int k = 0; k < 4; ++k) out->tile_rect[4 * g + k] = rect[k];
}

}  // namespace

void ProjectSplats(const ProjectionConstants& pc, const M4dGaussians& layer, int sh_degree,
                   size_t begin, size_t end, size_t offset, ProjectedSplats* out) {
  const int degree = std::min(sh_degree, static_cast<int>(layer.sh_degree));
  for (size_t i = begin; i < end; ++i) ProjectOne(pc, layer, degree, i, offset + i, out);
}

}  // namespace m4d
