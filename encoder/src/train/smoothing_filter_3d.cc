#include "encoder/src/train/smoothing_filter_3d.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace m4d {
namespace {

constexpr float kMargin = 0.15f;  // Mip-Splatting's: centres just outside an image count

float Sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// depth / fx if the camera sees p, else +infinity.
float SamplingSpacing(const Camera& c, const float* p) {
  const float* r = c.rotation;
  const float z = r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + c.translation[2];
  if (!(z > c.near_plane)) return std::numeric_limits<float>::infinity();
  const float x = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + c.translation[0];
  const float y = r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + c.translation[1];
  const float u = c.fx * x / z + c.cx, v = c.fy * y / z + c.cy;
  const float mu = kMargin * c.width, mv = kMargin * c.height;
  if (!(u >= -mu && u <= c.width + mu && v >= -mv && v <= c.height + mv)) {
    return std::numeric_limits<float>::infinity();
  }
  return z / c.fx;
}

}  // namespace

void SmoothingFilter3d::Fit(const GaussianModel& model, const std::vector<Camera>& cameras,
                            float variance, size_t unfiltered) {
  const size_t n = model.size();
  sigma_.assign(n, std::numeric_limits<float>::infinity());
  const float root = std::sqrt(variance);
  float largest = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    float spacing = std::numeric_limits<float>::infinity();
    for (const Camera& c : cameras) {
      spacing = std::min(spacing, SamplingSpacing(c, &model.positions[3 * i]));
    }
    sigma_[i] = root * spacing;
    if (std::isfinite(sigma_[i])) largest = std::max(largest, sigma_[i]);
  }
  for (float& s : sigma_) {
    if (!std::isfinite(s)) s = largest;
  }
  std::fill_n(sigma_.begin(), std::min(unfiltered, n), 0.0f);
}

void SmoothingFilter3d::Apply(const GaussianModel& model) {
  const size_t n = model.size();
  log_scales_.resize(3 * n);
  opacity_logits_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const float var = sigma_[i] * sigma_[i];
    if (var == 0.0f) {  // unfiltered, exactly
      std::copy_n(&model.log_scales[3 * i], 3, &log_scales_[3 * i]);
      opacity_logits_[i] = model.opacity_logits[i];
      continue;
    }
    float log_ratio = 0.0f;  // log of prod scale / scale'
    for (int a = 0; a < 3; ++a) {
      const float ls = model.log_scales[3 * i + a];
      const float filtered = 0.5f * std::log(std::exp(2.0f * ls) + var);
      log_scales_[3 * i + a] = filtered;
      log_ratio += ls - filtered;
    }
    const float o = Sigmoid(model.opacity_logits[i]) * std::exp(log_ratio);
    opacity_logits_[i] = std::log(o) - std::log1p(-o);
  }
}

M4dGaussians SmoothingFilter3d::View(const GaussianModel& model) const {
  M4dGaussians view = GaussianView(model);
  view.log_scales = log_scales_.data();
  view.opacity_logits = opacity_logits_.data();
  return view;
}

void SmoothingFilter3d::Backward(const GaussianModel& model, GaussianModel* gradients) const {
  for (size_t i = 0; i < model.size(); ++i) {
    const float var = sigma_[i] * sigma_[i];
    const float o = Sigmoid(model.opacity_logits[i]);
    const float filtered_o = Sigmoid(opacity_logits_[i]);
    const float g_logit = gradients->opacity_logits[i];
    for (int a = 0; a < 3; ++a) {
      const float s2 = std::exp(2.0f * model.log_scales[3 * i + a]);
      const float v = s2 + var;
      float& g = gradients->log_scales[3 * i + a];
      g = g * s2 / v + g_logit * (var / v) / (1.0f - filtered_o);
    }
    gradients->opacity_logits[i] = g_logit * (1.0f - o) / (1.0f - filtered_o);
  }
}

void SmoothingFilter3d::Bake(GaussianModel* model) const {
  std::copy(log_scales_.begin(), log_scales_.end(), model->log_scales.begin());
  std::copy(opacity_logits_.begin(), opacity_logits_.end(), model->opacity_logits.begin());
}

}  // namespace m4d
