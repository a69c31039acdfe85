// Backward of the rasterizer's preprocessing (sdk/src/render/splat_projection.h): from the
// gradients of one splat's 2D quantities to those of its Gaussian's coded values.
// Exact derivatives of the forward functions, including: the view-direction dependence of
// the SH colour on the position, the normalisation of the quaternion, the activations, and
// the clamped X/Z, Y/Z of the Jacobian (a clamped coordinate then depends on depth only).
// Clamped colour channels pass no gradient.
#ifndef M4D_ENCODER_RASTER_PROJECTION_BACKWARD_H_
#define M4D_ENCODER_RASTER_PROJECTION_BACKWARD_H_

#include <cstddef>
#include <cstdint>

#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/projection_constants.h"

namespace m4d {

// dL/d of one splat's 2D quantities, summed over pixels.
struct SplatGradient {
  float mean[2];   // projected mean u, v (pixels)
  float conic[3];  // a, b, c of power = -0.5 (a dx^2 + c dy^2) - b dx dy
  float opacity;
  float color[3];
};

// Caller-owned gradient arrays of one layer, laid out like its M4dGaussians.
struct LayerGradients {
  float* positions = nullptr;       // 3 per Gaussian
  float* log_scales = nullptr;      // 3 per Gaussian
  float* rotations = nullptr;       // 4 per Gaussian (with respect to the unnormalised value)
  float* opacity_logits = nullptr;  // 1 per Gaussian
  float* sh = nullptr;  // 3 * ShCoefficients(layer.sh_degree); zero beyond the active degree
};

// Writes the gradients of Gaussian i of `layer` (rendered with SH up to sh_degree, colour
// clamp flags `color_clamped`) into out at i.
void BackpropagateProjection(const ProjectionConstants& pc, const M4dGaussians& layer,
                             int sh_degree, size_t i, const SplatGradient& grad,
                             uint8_t color_clamped, const LayerGradients& out);

// Zeroes the gradients of Gaussian i (a culled one).
void ZeroGradients(const M4dGaussians& layer, size_t i, const LayerGradients& out);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_PROJECTION_BACKWARD_H_
