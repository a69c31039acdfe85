// The view-space (2D mean) gradient that drives densification, in the reference 3DGS's
// units. The reference differentiates with respect to the mean in normalised device
// coordinates: its pixel coordinate is ((ndc + 1) * size - 1) / 2, so
// dL/dndc = dL/dpixel * size / 2 per axis. Its densification compares the norm of that
// gradient, averaged over the views in which the Gaussian is visible, with 0.0002.
#ifndef M4D_ENCODER_RASTER_VIEWSPACE_GRADIENT_H_
#define M4D_ENCODER_RASTER_VIEWSPACE_GRADIENT_H_

#include <cmath>

namespace m4d {

// The reference's default densification threshold on |dL/dmean2D| in NDC units.
constexpr float kReferenceDensifyGradient = 0.0002f;

// |dL/dmean2D| in the reference's NDC units, from the gradient in pixels (SplatGradients
// mean2d) of an image of width x height.
inline float ViewspaceGradientNorm(const float dl_dmean_pixels[2], int width, int height) {
  const float gx = dl_dmean_pixels[0] * 0.5f * static_cast<float>(width);
  const float gy = dl_dmean_pixels[1] * 0.5f * static_cast<float>(height);
  return std::sqrt(gx * gx + gy * gy);
}

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_VIEWSPACE_GRADIENT_H_
