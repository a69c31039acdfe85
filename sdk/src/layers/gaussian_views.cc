#include "sdk/src/layers/gaussian_views.h"

#include <algorithm>
#include <cstring>

namespace m4d {

M4dGaussians GaussianView(const GaussianSet& set) {
  M4dGaussians g;
  std::memset(&g, 0, sizeof(g));
  g.count = static_cast<uint32_t>(set.size());
  g.sh_degree = static_cast<uint32_t>(set.sh_degree);
  g.sh_coefficients = static_cast<uint32_t>(ShCoefficients(set.sh_degree));
  if (g.count == 0) return g;
  g.positions = set.positions.data();
  g.log_scales = set.log_scales.data();
  g.rotations = set.rotations.data();
  g.opacity_logits = set.opacity_logits.data();
  g.sh = set.sh.data();
  return g;
}

Status AppendLayer(const M4dGaussians& layer, GaussianSet* out) {
  const size_t n = layer.count;
  if (n == 0) return Status::Ok();
  if (!layer.positions || !layer.log_scales || !layer.rotations || !layer.opacity_logits ||
      !layer.sh || layer.sh_degree > 3 ||
      layer.sh_coefficients != static_cast<uint32_t>(ShCoefficients(layer.sh_degree))) {
    return Status(M4D_ERR_INVALID_ARG, "a layer's arrays are inconsistent");
  }
  out->positions.insert(out->positions.end(), layer.positions, layer.positions + 3 * n);
  out->log_scales.insert(out->log_scales.end(), layer.log_scales, layer.log_scales + 3 * n);
  out->rotations.insert(out->rotations.end(), layer.rotations, layer.rotations + 4 * n);
  out->opacity_logits.insert(out->opacity_logits.end(), layer.opacity_logits,
                             layer.opacity_logits + n);
  // [k][r, g, b] per Gaussian; coefficients the layer does not have stay zero.
  const size_t have = 3 * layer.sh_coefficients, width = static_cast<size_t>(out->sh_floats());
  for (size_t i = 0; i < n; ++i) {
    const float* sh = layer.sh + i * have;
    out->sh.insert(out->sh.end(), sh, sh + std::min(have, width));
    out->sh.insert(out->sh.end(), width - std::min(have, width), 0.0f);
  }
  return Status::Ok();
}

}  // namespace m4d
