// The views of a set of Gaussians and every conversion between the SDK's containers, in one
// place. A GaussianSet owns a layer's Gaussians (allocated through the caller's hooks); an
// M4dGaussians is the public API's view of one (m4d.h); a GaussianLayerView is the renderers'
// view of one, with the SH degree as an int. All hold the values as coded (log scales,
// opacity logits, unnormalised quaternions w, x, y, z, SH [gaussian][k][r, g, b]). The
// encoder's trainable GaussianModel converts to and from a GaussianSet in gaussian_model.h.
#ifndef M4D_SDK_LAYERS_GAUSSIAN_VIEWS_H_
#define M4D_SDK_LAYERS_GAUSSIAN_VIEWS_H_

#include <cstddef>

#include "m4d/m4d.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// Several layers (a frame's static and dynamic sets) render together; Gaussians are indexed
// globally in concatenation order.
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

// The public view of a set: pointers into it, NULL when it is empty.
M4dGaussians GaussianView(const GaussianSet& set);

// Appends a public layer's Gaussians to `out`; a layer of a lower SH degree than out's gets
// zero higher coefficients. M4D_ERR_INVALID_ARG for inconsistent layer arrays.
Status AppendLayer(const M4dGaussians& layer, GaussianSet* out);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_GAUSSIAN_VIEWS_H_
