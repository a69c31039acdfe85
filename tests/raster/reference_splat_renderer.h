// A straightforward double-precision splat renderer for the rasterizer tests: no tiles, no
// vectors, every pixel against every Gaussian in depth order, written independently of the
// SDK's code but with the same rules (splat_projection.h, splat_alpha.h).
//
// It records its discrete decisions (culling, clamps, which Gaussian blends into which pixel
// and whether its alpha was clamped, where each pixel stopped) and can replay them, so that
// finite differences see one smooth piece of the piecewise-smooth image: exactly what an
// analytic gradient differentiates.
#ifndef M4D_TESTS_RASTER_REFERENCE_SPLAT_RENDERER_H_
#define M4D_TESTS_RASTER_REFERENCE_SPLAT_RENDERER_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"

namespace m4d {
namespace test {

// All parameters in double, so that any of them can be perturbed.
struct RefLayer {
  int sh_degree = 0;
  size_t count = 0;
  std::vector<double> positions, log_scales, rotations, opacity_logits, sh;
};

struct RefScene {
  std::vector<RefLayer> layers;
  // Optional offset (pixels, 2 per Gaussian) added to each projected mean: finite differences
  // in it give the gradient with respect to the 2D mean.
  std::vector<double> mean_offset;

  size_t size() const {
    size_t n = 0;
    for (const RefLayer& l : layers) n += l.count;
    return n;
  }
};

inline RefLayer ToRefLayer(const M4dGaussians& v) {
  RefLayer l;
  l.sh_degree = v.sh_degree;
  l.count = v.count;
  const size_t k = static_cast<size_t>((v.sh_degree + 1) * (v.sh_degree + 1));
  l.positions.assign(v.positions, v.positions + 3 * v.count);
  l.log_scales.assign(v.log_scales, v.log_scales + 3 * v.count);
  l.rotations.assign(v.rotations, v.rotations + 4 * v.count);
  l.opacity_logits.assign(v.opacity_logits, v.opacity_logits + v.count);
  l.sh.assign(v.sh, v.sh + 3 * k * v.count);
  return l;
}

struct RefDecisions {
  std::vector<bool> visible;              // per Gaussian
  std::vector<uint8_t> color_clamped;     // per Gaussian, bit per channel
  std::vector<uint8_t> jacobian_clamped;  // per Gaussian: 1 x low, 2 x high, 4 y low, 8 y high
  std::vector<std::vector<std::pair<int, bool>>> blended;  // per pixel: (Gaussian, alpha clamped)
  std::vector<bool> stopped;  // per pixel: stopped at the transmittance threshold
};

struct RefImage {
  std::vector<double> color;  // HWC
  std::vector<double> alpha;
};

struct RefSplat {
  double u = 0, v = 0, depth = 0, radius = 0;
  double conic[3] = {0, 0, 0};
  double opacity = 0;
  double color[3] = {0, 0, 0};
};

class ReferenceRenderer {
 public:
  ReferenceRenderer(const Camera& camera, int sh_degree, const float background[3])
      : camera_(camera), sh_degree_(sh_degree) {
    for (int c = 0; c < 3; ++c) background_[c] = background[c];
  }

  // Renders, recording the decisions into *decisions.
  RefImage Record(const RefScene& scene, RefDecisions* decisions) const {
    return Render(scene, decisions, true);
  }
  // Renders following recorded decisions.
  RefImage Replay(const RefScene& scene, RefDecisions decisions) const {
    return Render(scene, &decisions, false);
  }

  // The splats of the scene (recording decisions about the projection into *d).
  std::vector<RefSplat> Project(const RefScene& scene, RefDecisions* d, bool record) const {
    const size_t n = scene.size();
    if (record) {
      d->visible.assign(n, false);
      d->color_clamped.assign(n, 0);
      d->jacobian_clamped.assign(n, 0);
    }
    std::vector<RefSplat> splats(n);
    size_t g = 0;
    for (const RefLayer& layer : scene.layers) {
      for (size_t i = 0; i < layer.count; ++i, ++g) {
        bool visible = ProjectOne(layer, i, d, g, record, &splats[g]);
        if (record) d->visible[g] = visible;
        if (!scene.mean_offset.empty()) {
          splats[g].u += scene.mean_offset[2 * g];
          splats[g].v += scene.mean_offset[2 * g + 1];
        }
      }
    }
    return splats;
  }

 private:
  RefImage Render(const RefScene& scene, RefDecisions* d, bool record) const {
    const std::vector<RefSplat> splats = Project(scene, d, record);
    const int w = camera_.width, h = camera_.height;
    RefImage image;
    image.color.assign(3 * static_cast<size_t>(w) * h, 0.0);
    image.alpha.assign(static_cast<size_t>(w) * h, 0.0);
    std::vector<int> order;
    for (size_t g = 0; g < splats.size(); ++g) {
      if (d->visible[g]) order.push_back(static_cast<int>(g));
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return splats[a].depth < splats[b].depth; });
    if (record) {
      d->blended.assign(static_cast<size_t>(w) * h, {});
      d->stopped.assign(static_cast<size_t>(w) * h, false);
    }
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t p = static_cast<size_t>(y) * w + x;
        double t = 1.0, c[3] = {0, 0, 0};
        auto blend = [&](int g, double alpha) {
          for (int k = 0; k < 3; ++k) c[k] += splats[g].color[k] * alpha * t;
          t *= 1.0 - alpha;
        };
        if (record) {
          for (int g : order) {
            double alpha;
            bool clamped;
            if (!Alpha(splats[g], x + 0.5, y + 0.5, &alpha, &clamped)) continue;
            if (t * (1.0 - alpha) < 0.0001) {
              d->stopped[p] = true;
              break;
            }
            d->blended[p].push_back({g, clamped});
            blend(g, alpha);
          }
        } else {
          for (const auto& [g, clamped] : d->blended[p]) {
            const RefSplat& s = splats[g];
            const double dx = s.u - (x + 0.5), dy = s.v - (y + 0.5);
            blend(g, clamped ? 0.99 : s.opacity * std::exp(Power(s, dx, dy)));
          }
        }
        for (int k = 0; k < 3; ++k) image.color[3 * p + k] = c[k] + t * background_[k];
        image.alpha[p] = 1.0 - t;
      }
    }
    return image;
  }

  static double Power(const RefSplat& s, double dx, double dy) {
    return -0.5 * (s.conic[0] * dx * dx + s.conic[2] * dy * dy) - s.conic[1] * dx * dy;
  }

  // The rules of the rasterizer for one (splat, pixel centre) pair.
  static bool Alpha(const RefSplat& s, double px, double py, double* alpha, bool* clamped) {
    const double dx = s.u - px, dy = s.v - py;
    if (std::fabs(dx) > s.radius || std::fabs(dy) > s.radius) return false;
    const double power = Power(s, dx, dy);
    if (power > 0) return false;
    const double raw = s.opacity * std::exp(power);
    *clamped = raw > 0.99;
    *alpha = std::min(0.99, raw);
    return *alpha >= 1.0 / 255.0;
  }

  bool ProjectOne(const RefLayer& layer, size_t i, RefDecisions* d, size_t g, bool record,
                  RefSplat* s) const {
    const double* p = &layer.positions[3 * i];
    double t[3];
    for (int a = 0; a < 3; ++a) {
      t[a] = camera_.translation[a];
      for (int b = 0; b < 3; ++b) t[a] += double{camera_.rotation[3 * a + b]} * p[b];
    }
    const double opacity = 1.0 / (1.0 + std::exp(-layer.opacity_logits[i]));
    if (record && (t[2] <= camera_.near_plane || opacity < 1.0 / 255.0)) return false;

    // Covariance R S S^T R^T.
    const double* q = &layer.rotations[4 * i];
    const double qn = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / qn, x = q[1] / qn, y = q[2] / qn, z = q[3] / qn;
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    double s2[3];
    for (int a = 0; a < 3; ++a) s2[a] = std::exp(2 * layer.log_scales[3 * i + a]);
    double cov3[3][3];
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        cov3[a][b] = 0;
        for (int k = 0; k < 3; ++k) cov3[a][b] += r[a][k] * s2[k] * r[b][k];
      }
    }

    // EWA with clamped X/Z, Y/Z.
    const double fx = camera_.fx, fy = camera_.fy, wd = camera_.width, ht = camera_.height;
    const double lim[4] = {(-camera_.cx - 0.15 * wd) / fx, (wd - camera_.cx + 0.15 * wd) / fx,
                           (-camera_.cy - 0.15 * ht) / fy, (ht - camera_.cy + 0.15 * ht) / fy};
    double xz = t[0] / t[2], yz = t[1] / t[2];
    uint8_t jc = 0;
    if (record) {
      jc = (xz < lim[0] ? 1 : 0) | (xz > lim[1] ? 2 : 0) | (yz < lim[2] ? 4 : 0) |
           (yz > lim[3] ? 8 : 0);
      d->jacobian_clamped[g] = jc;
    } else {
      jc = d->jacobian_clamped[g];
    }
    if (jc & 1) xz = lim[0];
    if (jc & 2) xz = lim[1];
    if (jc & 4) yz = lim[2];
    if (jc & 8) yz = lim[3];
    const double jac[2][3] = {{fx / t[2], 0, -fx * xz / t[2]}, {0, fy / t[2], -fy * yz / t[2]}};
    double jw[2][3];
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 3; ++b) {
        jw[a][b] = 0;
        for (int k = 0; k < 3; ++k) jw[a][b] += jac[a][k] * camera_.rotation[3 * k + b];
      }
    }
    double cov2[2][2];
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        cov2[a][b] = 0;
        for (int k = 0; k < 3; ++k) {
          for (int l = 0; l < 3; ++l) cov2[a][b] += jw[a][k] * cov3[k][l] * jw[b][l];
        }
      }
    }
    cov2[0][0] += 0.3;
    cov2[1][1] += 0.3;
    const double det = cov2[0][0] * cov2[1][1] - cov2[0][1] * cov2[0][1];
    if (record && det <= 0) return false;
    s->conic[0] = cov2[1][1] / det;
    s->conic[1] = -cov2[0][1] / det;
    s->conic[2] = cov2[0][0] / det;
    const double mid = 0.5 * (cov2[0][0] + cov2[1][1]);
    s->radius = std::ceil(3 * std::sqrt(mid + std::sqrt(std::max(0.1, mid * mid - det))));
    s->u = fx * t[0] / t[2] + camera_.cx;
    s->v = fy * t[1] / t[2] + camera_.cy;
    s->depth = t[2];
    s->opacity = opacity;
    if (record && (s->u + s->radius < 0 || s->u - s->radius > wd || s->v + s->radius < 0 ||
                   s->v - s->radius > ht)) {
      return false;
    }

    // Colour, SH in the direction from the camera centre.
    double centre[3];
    for (int a = 0; a < 3; ++a) {
      centre[a] = 0;
      for (int k = 0; k < 3; ++k)
        centre[a] -= double{camera_.rotation[3 * k + a]} * camera_.translation[k];
    }
    double dir[3], len = 0;
    for (int a = 0; a < 3; ++a) {
      dir[a] = p[a] - centre[a];
      len += dir[a] * dir[a];
    }
    len = std::sqrt(len);
    double basis[16];
    ShBasisD(std::min(sh_degree_, layer.sh_degree), dir[0] / len, dir[1] / len, dir[2] / len,
             basis);
    const int active =
        (std::min(sh_degree_, layer.sh_degree) + 1) * (std::min(sh_degree_, layer.sh_degree) + 1);
    const int stored = (layer.sh_degree + 1) * (layer.sh_degree + 1);
    uint8_t clamped = 0;
    for (int c = 0; c < 3; ++c) {
      double v = 0.5;
      for (int k = 0; k < active; ++k) v += basis[k] * layer.sh[(i * stored + k) * 3 + c];
      const bool clamp = record ? v < 0 : ((d->color_clamped[g] >> c) & 1) != 0;
      if (clamp) clamped |= static_cast<uint8_t>(1 << c);
      s->color[c] = clamp ? 0.0 : v;
    }
    if (record) d->color_clamped[g] = clamped;
    return true;
  }

  // The SH basis, written out from the real spherical harmonics with the reference 3DGS
  // signs and normalisation.
  static void ShBasisD(int degree, double x, double y, double z, double* b) {
    const double c0 = 0.28209479177387814, c1 = 0.4886025119029199;
    b[0] = c0;
    if (degree < 1) return;
    b[1] = -c1 * y;
    b[2] = c1 * z;
    b[3] = -c1 * x;
    if (degree < 2) return;
    b[4] = 1.0925484305920792 * x * y;
    b[5] = -1.0925484305920792 * y * z;
    b[6] = 0.31539156525252005 * (2 * z * z - x * x - y * y);
    b[7] = -1.0925484305920792 * x * z;
    b[8] = 0.5462742152960396 * (x * x - y * y);
    if (degree < 3) return;
    b[9] = -0.5900435899266435 * y * (3 * x * x - y * y);
    b[10] = 2.890611442640554 * x * y * z;
    b[11] = -0.4570457994644658 * y * (4 * z * z - x * x - y * y);
    b[12] = 0.3731763325901154 * z * (2 * z * z - 3 * x * x - 3 * y * y);
    b[13] = -0.4570457994644658 * x * (4 * z * z - x * x - y * y);
    b[14] = 1.445305721320277 * z * (x * x - y * y);
    b[15] = -0.5900435899266435 * x * (x * x - 3 * y * y);
  }

  Camera camera_;
  int sh_degree_;
  double background_[3];
};

}  // namespace test
}  // namespace m4d

#endif  // M4D_TESTS_RASTER_REFERENCE_SPLAT_RENDERER_H_
