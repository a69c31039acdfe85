#include "encoder/src/motion/motion_field.h"

#include <cstring>

#include "encoder/src/motion/rigid_update.h"

namespace m4d {

void ZeroGrid(const GridConfig& config, const MotionStencil& stencil, MotionParameters* params) {
  for (int l = 0; l < kMaxGridLevels; ++l) {
    size_t n = l < config.num_levels ? stencil.active[l].size() * config.channels[l] : 0;
    params->grid[l].assign(n, 0.0f);
  }
}

void MotionField::Forward(const GridConfig& config, const float* steps,
                          const MotionStencil& stencil, const MotionParameters& params,
                          const float* positions, const float* rotations, float* moved_positions,
                          float* moved_rotations) {
  config_ = &config;
  steps_ = steps;
  stencil_ = &stencil;
  params_ = &params;
  rotations_ = rotations;
  const size_t n = stencil.gaussian_count;
  moved_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (stencil.inside[i]) moved_.push_back(static_cast<uint32_t>(i));
  }
  features_.resize(config.feature_count(), static_cast<Eigen::Index>(moved_.size()));
  for (size_t m = 0; m < moved_.size(); ++m) {
    const size_t i = moved_[m];
    int f = 0;
    for (int l = 0; l < config.num_levels; ++l) {
      const int channels = config.channels[l];
      const uint32_t* corner = &stencil.corner[l][8 * i];
      const float* w = &stencil.weight[l][8 * i];
      const float* grid = params.grid[l].data();
      for (int c = 0; c < channels; ++c) {
        // The spec's order of operations (6.3 step 2).
        float acc = 0.0f;
        for (int k = 0; k < 8; ++k) acc = acc + w[k] * grid[corner[k] * channels + c];
        features_(f++, static_cast<Eigen::Index>(m)) = acc * steps[l];
      }
    }
  }
  MlpForward(params.mlp, features_, &batch_);
  std::memcpy(moved_positions, positions, 3 * n * sizeof(float));
  std::memcpy(moved_rotations, rotations, 4 * n * sizeof(float));
  const Eigen::MatrixXf& out = batch_.outputs.back();
  for (size_t m = 0; m < moved_.size(); ++m) {
    const size_t i = moved_[m];
    RigidUpdate(&out(0, static_cast<Eigen::Index>(m)), positions + 3 * i, rotations + 4 * i,
                moved_positions + 3 * i, moved_rotations + 4 * i);
  }
}

void MotionField::Backward(const float* d_positions, const float* d_rotations, bool mlp_gradient,
                           MotionParameters* grad) {
  const Eigen::MatrixXf& out = batch_.outputs.back();
  Eigen::MatrixXf d_out(out.rows(), out.cols());
  for (size_t m = 0; m < moved_.size(); ++m) {
    const size_t i = moved_[m];
    const auto col = static_cast<Eigen::Index>(m);
    RigidUpdateBackward(&out(0, col), rotations_ + 4 * i, d_positions + 3 * i, d_rotations + 4 * i,
                        &d_out(0, col));
  }
  Eigen::MatrixXf d_features;
  MlpBackward(params_->mlp, features_, batch_, d_out, mlp_gradient ? &grad->mlp : nullptr,
              &d_features);
  for (size_t m = 0; m < moved_.size(); ++m) {
    const size_t i = moved_[m];
    int f = 0;
    for (int l = 0; l < config_->num_levels; ++l) {
      const int channels = config_->channels[l];
      const uint32_t* corner = &stencil_->corner[l][8 * i];
      const float* w = &stencil_->weight[l][8 * i];
      float* g = grad->grid[l].data();
      for (int c = 0; c < channels; ++c) {
        const float d = d_features(f++, static_cast<Eigen::Index>(m)) * steps_[l];
        for (int k = 0; k < 8; ++k) g[corner[k] * channels + c] += w[k] * d;
      }
    }
  }
}

}  // namespace m4d
