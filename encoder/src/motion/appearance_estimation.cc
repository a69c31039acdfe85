#include "encoder/src/motion/appearance_estimation.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/layers/appearance_update_writer.h"

namespace m4d {

std::vector<int> AppearanceCheckViews(int view_count, int every) {
  std::vector<int> views;
  for (int v = every - 1; every > 0 && v < view_count; v += every) views.push_back(v);
  return views;
}

bool AnyAppearanceCheckView(const std::vector<int>& views, int every) {
  for (int v : views) {
    if (every > 0 && v % every == every - 1) return true;
  }
  return false;
}

AppearanceEstimation::AppearanceEstimation(size_t gaussians, float step, float learning_rate,
                                           float entropy_learning_rate)
    : n_(gaussians),
      step_(step),
      values_(3 * gaussians, 0.0f),
      noisy_(3 * gaussians, 0.0f),
      grad_(3 * gaussians, 0.0f),
      learning_rate_(learning_rate),
      entropy_(3) {
  parameter_ = adam_.AddParameter(3);
  adam_.ResizeRows(n_);
  adam_.AddGroup("appearance", parameter_, 0, 3, learning_rate);
  entropy_parameter_ = entropy_adam_.AddParameter(LogisticEntropyModel::kParameters);
  entropy_adam_.ResizeRows(3);
  entropy_adam_.AddGroup("entropy", entropy_parameter_, 0, LogisticEntropyModel::kParameters,
                         entropy_learning_rate);
  entropy_grad_.assign(entropy_.parameters().size(), 0.0f);
}

const float* AppearanceEstimation::NoisySh(const GaussianSet& set, bool simulate_quantization,
                                           TrainingRandom* rng) {
  const size_t stride = static_cast<size_t>(set.sh_floats());
  sh_.assign(set.sh.begin(), set.sh.end());
  for (size_t k = 0; k < values_.size(); ++k) {
    noisy_[k] = values_[k] + (simulate_quantization ? rng->Uniform() - 0.5f : 0.0f);
    sh_[(k / 3) * stride + k % 3] += noisy_[k] * step_;
  }
  return sh_.data();
}

void AppearanceEstimation::Step(const float* d_dc, double rate_weight, float lr_scale) {
  for (size_t k = 0; k < values_.size(); ++k) grad_[k] = d_dc[k] * step_;
  std::fill(entropy_grad_.begin(), entropy_grad_.end(), 0.0f);
  const float weight = static_cast<float>(rate_weight);
  for (int c = 0; c < 3; ++c) {
    entropy_.Bits(c, noisy_.data() + c, n_, 3, weight, grad_.data() + c, entropy_grad_.data());
  }
  adam_.SetLearningRate(0, learning_rate_ * lr_scale);
  adam_.Step(parameter_, values_.data(), grad_.data(), nullptr);
  entropy_adam_.Step(entropy_parameter_, entropy_.parameters().data(), entropy_grad_.data(),
                     nullptr);
}

std::vector<int32_t> AppearanceEstimation::Rounded() const {
  std::vector<int32_t> q(values_.size());
  const float limit = static_cast<float>(kMaxAppearanceValue);
  for (size_t k = 0; k < q.size(); ++k) {
    q[k] = static_cast<int32_t>(std::clamp(std::nearbyint(values_[k]), -limit, limit));
  }
  return q;
}

double AppearanceEstimation::Bits(const std::vector<int32_t>& values) const {
  std::vector<float> y(values.begin(), values.end());
  double bits = 0;
  for (int c = 0; c < 3; ++c) {
    bits += entropy_.Bits(c, y.data() + c, y.size() / 3, 3, 0.0f, nullptr, nullptr);
  }
  return bits;
}

}  // namespace m4d
