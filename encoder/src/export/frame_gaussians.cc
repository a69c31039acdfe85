#include "encoder/src/export/frame_gaussians.h"

#include <algorithm>

namespace m4d {
namespace {

Status Append(const M4dGaussians& layer, GaussianSet* out) {
  const size_t n = layer.count;
  if (n == 0) return Status::Ok();
  if (!layer.positions || !layer.log_scales || !layer.rotations || !layer.opacity_logits ||
      !layer.sh || layer.sh_degree > 3 ||
      layer.sh_coefficients != static_cast<uint32_t>(ShCoefficients(layer.sh_degree))) {
    return Status(M4D_ERR_INVALID_ARG, "GaussianSetFromFrame: inconsistent layer arrays");
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

}  // namespace

Status GaussianSetFromFrame(const M4dFrame& frame, uint32_t layers, GaussianSet* out) {
  *out = GaussianSet();
  const bool with_static = (layers & M4D_LAYER_STATIC) != 0;
  const bool with_dynamic = (layers & M4D_LAYER_DYNAMIC) != 0;
  out->sh_degree = static_cast<int>(std::max(with_static ? frame.static_layer.sh_degree : 0u,
                                             with_dynamic ? frame.dynamic_layer.sh_degree : 0u));
  if (with_static) M4D_RETURN_IF_ERROR(Append(frame.static_layer, out));
  if (with_dynamic) M4D_RETURN_IF_ERROR(Append(frame.dynamic_layer, out));
  return Status::Ok();
}

}  // namespace m4d
