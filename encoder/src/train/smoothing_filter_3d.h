// Mip-Splatting's 3D smoothing filter (Yu et al., CVPR 2024): a Gaussian may not be finer than
// the finest sampling of the training cameras that see it, so each is convolved with an
// isotropic Gaussian of variance `variance` x (depth / focal)^2 at its closest such camera.
// Training renders the filtered model; the filter is baked into the Gaussians before they are
// coded, so the decoder renders plain 3D Gaussians and does not change.
//
// Filtered: scale_a' = sqrt(scale_a^2 + sigma^2) per axis (the filter is isotropic, so it adds
// to the covariance's eigenvalues), opacity' = opacity x prod_a scale_a / scale_a' (the
// footprint's integral is kept).
#ifndef M4D_ENCODER_TRAIN_SMOOTHING_FILTER_3D_H_
#define M4D_ENCODER_TRAIN_SMOOTHING_FILTER_3D_H_

#include <cstddef>
#include <vector>

#include "encoder/src/train/gaussian_model.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"

namespace m4d {

class SmoothingFilter3d {
 public:
  // Each Gaussian's sigma from its centre: sqrt(variance) x depth / fx at the camera of
  // smallest such ratio among those whose image (grown by 15 % on each side) holds the centre
  // in front of the near plane; the largest sigma for a Gaussian no camera sees. The first
  // `unfiltered` Gaussians (frozen ones) get none and stay exactly as they are.
  void Fit(const GaussianModel& model, const std::vector<Camera>& cameras, float variance,
           size_t unfiltered = 0);
  // The filtered scales and opacities of `model` (the size Fit saw).
  void Apply(const GaussianModel& model);
  // `model`'s layer with the filtered scales and opacities of the last Apply.
  M4dGaussians View(const GaussianModel& model) const;
  // Turns the gradients with respect to the filtered log-scales and opacity logits into those
  // with respect to the model's, in place.
  void Backward(const GaussianModel& model, GaussianModel* gradients) const;
  // Writes the filtered values of the last Apply into `model`.
  void Bake(GaussianModel* model) const;

  size_t size() const { return sigma_.size(); }
  const std::vector<float>& sigma() const { return sigma_; }

 private:
  std::vector<float> sigma_;
  std::vector<float> log_scales_;      // filtered, 3 per Gaussian
  std::vector<float> opacity_logits_;  // filtered
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_SMOOTHING_FILTER_3D_H_
