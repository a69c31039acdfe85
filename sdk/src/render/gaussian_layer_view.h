// GaussianLayerView: a read-only view of one layer's Gaussians for rendering, as coded (log
// scales, opacity logits, unnormalised quaternions w, x, y, z, SH [gaussian][k][r, g, b]).
// Several layers (a frame's static and dynamic sets) render together; Gaussians are indexed
// globally in concatenation order.
#ifndef M4D_RENDER_GAUSSIAN_LAYER_VIEW_H_
#define M4D_RENDER_GAUSSIAN_LAYER_VIEW_H_

#include <cstddef>

#include "m4d/m4d.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

struct GaussianLayerView {
  size_t count = 0;
  int sh_degree = 0;                      // 0..3
  const float* positions = nullptr;       // 3 per Gaussian
  const float* log_scales = nullptr;      // 3 per Gaussian
  const float* rotations = nullptr;       // 4 per Gaussian
  const float* opacity_logits = nullptr;  // 1 per Gaussian
  const float* sh = nullptr;              // 3 * ShCoefficients(sh_degree) per Gaussian
};

inline GaussianLayerView LayerView(const GaussianSet& set) {
  GaussianLayerView v;
  v.count = set.size();
  v.sh_degree = set.sh_degree;
  v.positions = set.positions.data();
  v.log_scales = set.log_scales.data();
  v.rotations = set.rotations.data();
  v.opacity_logits = set.opacity_logits.data();
  v.sh = set.sh.data();
  return v;
}

inline GaussianLayerView LayerView(const M4dGaussians& g) {
  GaussianLayerView v;
  v.count = g.count;
  v.sh_degree = static_cast<int>(g.sh_degree);
  v.positions = g.positions;
  v.log_scales = g.log_scales;
  v.rotations = g.rotations;
  v.opacity_logits = g.opacity_logits;
  v.sh = g.sh;
  return v;
}

}  // namespace m4d

#endif  // M4D_RENDER_GAUSSIAN_LAYER_VIEW_H_
