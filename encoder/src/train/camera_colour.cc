#include "encoder/src/train/camera_colour.h"

#include <cmath>

namespace m4d {

void CameraColour::Init(int views, float learning_rate) {
  learning_rate_ = learning_rate;
  state_.assign(learning_rate > 0 ? kStride * static_cast<size_t>(views) : 0, 0.0f);
}

void CameraColour::Apply(int view, Image* render) const {
  const float* t = terms(view);
  const float gain[3] = {std::exp(t[0]), std::exp(t[1]), std::exp(t[2])};
  for (size_t p = 0; p < render->pixels.size(); p += 3) {
    for (int c = 0; c < 3; ++c) render->pixels[p + c] = gain[c] * render->pixels[p + c] + t[3 + c];
  }
}

void CameraColour::Backward(int view, const Image& corrected, Image* gradient) {
  float* t = &state_[kStride * static_cast<size_t>(view)];
  const float gain[3] = {std::exp(t[0]), std::exp(t[1]), std::exp(t[2])};
  double grad[6] = {0, 0, 0, 0, 0, 0};
  for (size_t p = 0; p < gradient->pixels.size(); p += 3) {
    for (int c = 0; c < 3; ++c) {
      const float d = gradient->pixels[p + c];
      grad[c] += d * (corrected.pixels[p + c] - t[3 + c]);  // d / dg of gain * raw
      grad[3 + c] += d;
      gradient->pixels[p + c] = d * gain[c];
    }
  }
  // Adam without bias correction (beta1 0.9, beta2 0.999): the first steps are at most a few
  // learning rates, and a term is stepped once per pass over the views.
  for (int k = 0; k < 6; ++k) {
    float& m = t[6 + k];
    float& v = t[12 + k];
    const float g = static_cast<float>(grad[k]);
    m = 0.9f * m + 0.1f * g;
    v = 0.999f * v + 0.001f * g * g;
    t[k] -= learning_rate_ * m / (std::sqrt(v) + 1e-12f);
  }
  RemoveCommonPart();
}

void CameraColour::RemoveCommonPart() {
  const size_t views = state_.size() / kStride;
  for (size_t k = 0; k < 6; ++k) {
    double sum = 0;
    for (size_t v = 0; v < views; ++v) sum += state_[kStride * v + k];
    const float mean = static_cast<float>(sum / static_cast<double>(views));
    for (size_t v = 0; v < views; ++v) state_[kStride * v + k] -= mean;
  }
}

}  // namespace m4d
