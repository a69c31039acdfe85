// GaussianModel: the trainable Gaussians of a training stage, as the coded values the
// rasterizer and the bitstream use (log scales, opacity logits, unnormalised quaternions
// w, x, y, z, SH [gaussian][k][r, g, b]) in plain vectors, one per parameter, so that the
// optimizer and densification treat every parameter as rows of floats. SH is stored up to
// sh_degree (3 for keyframes) even while training renders fewer bands.
//
// A second GaussianModel of the same size holds the gradients (GradientView).
#ifndef M4D_ENCODER_TRAIN_GAUSSIAN_MODEL_H_
#define M4D_ENCODER_TRAIN_GAUSSIAN_MODEL_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/src/raster/projection_backward.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_views.h"

namespace m4d {

// The parameters, in the order the optimizer registers them.
enum GaussianParameter : int {
  kParamPositions,
  kParamLogScales,
  kParamRotations,
  kParamOpacityLogits,
  kParamSh,
  kGaussianParameterCount
};

struct GaussianModel {
  int sh_degree = 3;
  std::vector<float> positions;       // 3 per Gaussian
  std::vector<float> log_scales;      // 3 per Gaussian
  std::vector<float> rotations;       // 4 per Gaussian
  std::vector<float> opacity_logits;  // 1 per Gaussian
  std::vector<float> sh;              // 3 * ShCoefficients(sh_degree) per Gaussian

  size_t size() const { return opacity_logits.size(); }
  int sh_floats() const { return 3 * ShCoefficients(sh_degree); }
  // Floats per Gaussian of parameter p.
  int width(GaussianParameter p) const;
  std::vector<float>& values(GaussianParameter p);
  const std::vector<float>& values(GaussianParameter p) const;

  // Sets the count, keeping the first min(old, n) Gaussians; new ones are zero.
  void Resize(size_t n);
  // Appends copies of the listed Gaussians; keeps the Gaussians with keep[i] != 0.
  void AppendCopies(const std::vector<uint32_t>& rows);
  // Appends every Gaussian of `other` (same SH degree).
  void Append(const GaussianModel& other);
  void Keep(const std::vector<uint8_t>& keep);
};

// The row-major rotation matrix of quaternion q (w, x, y, z), normalised first; the identity
// for a zero quaternion.
void QuaternionMatrix(const float* q, float r[9]);

// For RenderForward.
M4dGaussians GaussianView(const GaussianModel& model);
// For RenderBackward: a model used as gradient storage (same size and SH degree as the
// rendered model).
LayerGradients GradientView(GaussianModel* gradients);

// The model of a coded set with SH stored up to sh_degree (higher bands zero; bands above
// sh_degree dropped). sh_degree must be 0..3.
Status ModelFromGaussianSet(const GaussianSet& set, int sh_degree, GaussianModel* model);
// The coded set with SH up to sh_degree (0..model.sh_degree; higher bands dropped).
Status ModelToGaussianSet(const GaussianModel& model, int sh_degree, GaussianSet* set);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_GAUSSIAN_MODEL_H_
