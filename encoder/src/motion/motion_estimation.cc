#include "encoder/src/motion/motion_estimation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "encoder/src/motion/appearance_estimation.h"
#include "encoder/src/motion/view_batch_gradients.h"
#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/frozen_layer_views.h"
#include "encoder/src/train/training_random.h"

namespace m4d {
namespace {

constexpr float kMaxGridValue = 2047.0f;       // what the grid writer can code (+-2047)
constexpr double kBitsPerRateUnit = 100000.0;  // L_rate in units of 100 kilobits

// One Adam per tensor: the optimizer keeps one row count for all its parameters.
struct TensorAdam {
  AdamOptimizer adam;
  int parameter = 0;

  TensorAdam(size_t rows, int width, float lr) {
    parameter = adam.AddParameter(width);
    adam.ResizeRows(rows);
    adam.AddGroup("values", parameter, 0, width, lr);
  }
  void SetLearningRate(float lr) { adam.SetLearningRate(0, lr); }
  void Step(std::vector<float>* values, const std::vector<float>& grad) {
    adam.Step(parameter, values->data(), grad.data(), nullptr);
  }
};

// The dynamic set with moved positions and rotations (and changed colours), for rendering.
M4dGaussians MovedView(const GaussianSet& set, const std::vector<float>& positions,
                       const std::vector<float>& rotations, const float* sh) {
  M4dGaussians view = GaussianView(set);
  view.positions = positions.data();
  view.rotations = rotations.data();
  if (sh) view.sh = sh;
  return view;
}

// The MLP's gradient only when it is trained (a GOP's first inter frame).
void ZeroParameters(bool with_mlp, MotionParameters* p) {
  for (auto& level : p->grid) std::fill(level.begin(), level.end(), 0.0f);
  if (!with_mlp) return;
  for (MlpLayer& layer : p->mlp.layers) {
    std::fill(layer.weights.begin(), layer.weights.end(), 0.0f);
    std::fill(layer.biases.begin(), layer.biases.end(), 0.0f);
  }
}

void RoundGrid(MotionParameters* p) {
  for (auto& level : p->grid) {
    for (float& v : level) v = std::clamp(std::nearbyint(v), -kMaxGridValue, kMaxGridValue);
  }
}

}  // namespace

MotionEstimator::MotionEstimator(const GridConfig& config, const MlpConfig& mlp_config,
                                 const float* steps)
    : config_(config), mlp_config_(mlp_config), entropy_(config.feature_count()) {
  std::copy(steps, steps + kMaxGridLevels, steps_);
  StartGop(0);
}

void MotionEstimator::StartGop(uint64_t seed) {
  // A small last layer: motion starts near zero and the grid sets its size.
  mlp_ = InitialMotionMlp(config_.feature_count(), mlp_config_, 0.1f,
                          static_cast<uint32_t>(seed ^ (seed >> 32)));
  for (int l = 0; l < kMaxGridLevels; ++l) {
    previous_active_[l].clear();
    previous_values_[l].clear();
  }
}

double MotionEstimator::RateAndGradient(const MotionParameters& noisy, double weight,
                                        MotionParameters* grad, std::vector<float>* entropy_grad,
                                        ThreadPool* pool) const {
  // Bits of the whole grid (voxels outside the stencil are zero); gradients are of
  // weight * bits.
  const float scale = static_cast<float>(weight);
  float* d_params = entropy_grad ? entropy_grad->data() : nullptr;
  struct Distribution {
    int level, channel;
  };
  std::vector<Distribution> distributions;
  for (int l = 0; l < config_.num_levels; ++l) {
    for (int c = 0; c < config_.channels[l]; ++c) distributions.push_back({l, c});
  }
  std::vector<double> bits(distributions.size()), idle_bits(distributions.size());
  auto measure = [&](size_t d, int) {
    const int l = distributions[d].level, c = distributions[d].channel;
    const int channels = config_.channels[l];
    const size_t active = noisy.grid[l].size() / channels;
    const double idle = static_cast<double>(config_.level_values(l) / channels) - active;
    const int id = static_cast<int>(d);
    bits[d] = entropy_.Bits(id, noisy.grid[l].data() + c, active, channels, scale,
                            grad ? grad->grid[l].data() + c : nullptr, d_params);
    const float zero = 0.0f;
    idle_bits[d] =
        idle * entropy_.Bits(id, &zero, 1, 1, static_cast<float>(idle) * scale, nullptr, d_params);
  };
  if (pool) {
    pool->Run(distributions.size(), measure);
  } else {
    for (size_t d = 0; d < distributions.size(); ++d) measure(d, 0);
  }
  double total = 0;
  for (size_t d = 0; d < distributions.size(); ++d) total = total + bits[d] + idle_bits[d];
  return total;
}

Status MotionEstimator::Estimate(const TrainingViews& views, const GaussianSet& static_set,
                                 const GaussianSet& dynamic_set, const GridBox& box,
                                 const MotionEstimationOptions& options,
                                 MotionEstimationResult* result, FrozenLayerViews* static_views) {
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  if (views.size() == 0 || options.iterations < 0) {
    return Status(M4D_ERR_INVALID_ARG, "motion estimation: no views or negative iterations");
  }
  const size_t n = dynamic_set.size();
  MotionStencil& stencil = result->stencil;
  BuildMotionStencil(config_, box, dynamic_set.positions.data(), n, &stencil);
  result->box = box;

  // Each frame fits its own entropy model from the prior (a peak at zero), as the stream codes
  // each grid with its own histogram. Carried over from the last frame, the model had widened to
  // its non-zero values, which then cost little in the rate term: more of them, a wider model
  // again, and a GOP's inter frames grew 1.5x on Panoptic
  // (docs/results/2026-11-30-entropy-model-per-frame.md).
  entropy_ = LogisticEntropyModel(config_.feature_count());
  MotionParameters params;
  ZeroGrid(config_, stencil, &params);
  if (options.warm_start) {
    for (int l = 0; l < config_.num_levels; ++l) {
      const int channels = config_.channels[l];
      const std::vector<uint32_t>& prev = previous_active_[l];
      for (size_t v = 0; v < stencil.active[l].size(); ++v) {
        auto it = std::lower_bound(prev.begin(), prev.end(), stencil.active[l][v]);
        if (it == prev.end() || *it != stencil.active[l][v]) continue;
        const size_t p = static_cast<size_t>(it - prev.begin());
        std::memcpy(&params.grid[l][v * channels], &previous_values_[l][p * channels],
                    channels * sizeof(float));
      }
    }
  }
  params.mlp = mlp_;
  MotionParameters grad = params;
  MotionParameters noisy = params;

  std::vector<std::unique_ptr<TensorAdam>> grid_adam, mlp_adam;
  for (int l = 0; l < config_.num_levels; ++l) {
    grid_adam.push_back(std::make_unique<TensorAdam>(stencil.active[l].size(), config_.channels[l],
                                                     options.grid_learning_rate));
  }
  for (const MlpLayer& layer : params.mlp.layers) {
    mlp_adam.push_back(std::make_unique<TensorAdam>(1, static_cast<int>(layer.weights.size()),
                                                    options.mlp_learning_rate));
    mlp_adam.push_back(std::make_unique<TensorAdam>(1, static_cast<int>(layer.biases.size()),
                                                    options.mlp_learning_rate));
  }
  TensorAdam entropy_adam(static_cast<size_t>(entropy_.distributions()),
                          LogisticEntropyModel::kParameters, options.entropy_learning_rate);
  std::vector<float> entropy_grad(entropy_.parameters().size());

  RenderSettings settings;
  settings.sh_degree = options.sh_degree;
  options.context.ApplyTo(&settings);
  std::unique_ptr<FrozenLayerViews> own_views;
  if (!static_views) {
    own_views =
        std::make_unique<FrozenLayerViews>(GaussianView(static_set), settings, views.size());
    static_views = own_views.get();
  }
  ViewBatchGradients batch_gradients(views, settings, options.ssim_weight, static_views);
  ViewBatchResult gradients;
  std::vector<float> moved_p(3 * n), moved_q(4 * n);

  TrainingRandom rng(options.context.seed);
  std::vector<int> order;
  size_t cursor = 0;
  MotionField field;
  double color_sum = 0;
  int color_count = 0;
  std::unique_ptr<AppearanceEstimation> appearance;
  if (options.appearance_step > 0) {
    appearance = std::make_unique<AppearanceEstimation>(n, options.appearance_step,
                                                        options.appearance_learning_rate,
                                                        options.entropy_learning_rate);
  }
  const int batch = std::clamp(options.views_per_step, 1, views.size());
  std::vector<int> batch_views;
  for (int it = 0; it < options.iterations; ++it) {
    // The grid's rate decays tenfold over the frame: fast to the motion, then settled.
    const float decay = std::pow(0.1f, static_cast<float>(it) / std::max(1, options.iterations));
    for (auto& adam : grid_adam) adam->SetLearningRate(options.grid_learning_rate * decay);
    for (int l = 0; l < config_.num_levels; ++l) {
      for (size_t k = 0; k < params.grid[l].size(); ++k) {
        noisy.grid[l][k] =
            params.grid[l][k] + (options.simulate_quantization ? rng.Uniform() - 0.5f : 0.0f);
      }
    }
    noisy.mlp = params.mlp;
    field.Forward(config_, steps_, stencil, noisy, dynamic_set.positions.data(),
                  dynamic_set.rotations.data(), moved_p.data(), moved_q.data());
    const float* sh = appearance
                          ? appearance->NoisySh(dynamic_set, options.simulate_quantization, &rng)
                          : nullptr;
    const M4dGaussians layers[2] = {GaussianView(static_set),
                                    MovedView(dynamic_set, moved_p, moved_q, sh)};
    batch_views.clear();
    int pass_start = 0;  // the batch's first view of the current pass through the views
    for (int b = 0; b < batch; ++b) {
      if (cursor == order.size()) {
        order.resize(views.size());
        for (int v = 0; v < views.size(); ++v) order[v] = v;
        rng.Shuffle(&order);
        cursor = 0;
        color_sum = 0;
        color_count = 0;
        pass_start = b;
      }
      batch_views.push_back(order[cursor++]);
    }
    M4D_RETURN_IF_ERROR(
        batch_gradients.Compute(layers, batch_views, appearance != nullptr, &gradients));
    for (int b = pass_start; b < batch; ++b) color_sum += gradients.losses[b];
    color_count += batch - pass_start;
    ZeroParameters(options.train_mlp, &grad);
    field.Backward(gradients.positions.data(), gradients.rotations.data(), options.train_mlp,
                   &grad);
    if (options.rate_term) {
      std::fill(entropy_grad.begin(), entropy_grad.end(), 0.0f);
      RateAndGradient(noisy, options.rate_weight / kBitsPerRateUnit, &grad, &entropy_grad,
                      batch_gradients.pool());
      entropy_adam.Step(&entropy_.parameters(), entropy_grad);
    }
    for (int l = 0; l < config_.num_levels; ++l) grid_adam[l]->Step(&params.grid[l], grad.grid[l]);
    if (appearance && !AnyAppearanceCheckView(batch_views, options.appearance_check_every)) {
      const double rate = options.rate_term ? options.rate_weight / kBitsPerRateUnit : 0.0;
      appearance->Step(gradients.dc.data(), rate, decay);
    }
    if (options.train_mlp) {
      for (size_t j = 0; j < params.mlp.layers.size(); ++j) {
        mlp_adam[2 * j]->Step(&params.mlp.layers[j].weights, grad.mlp.layers[j].weights);
        mlp_adam[2 * j + 1]->Step(&params.mlp.layers[j].biases, grad.mlp.layers[j].biases);
      }
      ZeroMotionAtZeroFeatures(&params.mlp);
    }
  }
  result->color_loss = color_count ? color_sum / color_count : 0.0;

  RoundGrid(&params);
  result->rate_bits = RateAndGradient(params, 0.0, nullptr, nullptr, nullptr);
  field.Forward(config_, steps_, stencil, params, dynamic_set.positions.data(),
                dynamic_set.rotations.data(), moved_p.data(), moved_q.data());
  result->motion.assign(7 * n, 0.0f);
  const Eigen::MatrixXf& out = field.outputs();
  for (size_t m = 0; m < field.moved().size(); ++m) {
    std::memcpy(&result->motion[7 * field.moved()[m]], &out(0, static_cast<Eigen::Index>(m)),
                7 * sizeof(float));
  }
  if (appearance) {
    result->appearance = appearance->Rounded();
    result->appearance_bits = appearance->Bits(result->appearance);
  } else {
    result->appearance.clear();
    result->appearance_bits = 0;
  }
  if (options.train_mlp) mlp_ = params.mlp;
  for (int l = 0; l < config_.num_levels; ++l) {
    previous_active_[l] = stencil.active[l];
    previous_values_[l] = params.grid[l];
  }
  result->parameters = std::move(params);
  return Status::Ok();
}

GridBox DynamicGridBox(const GaussianSet& dynamic_set, float lower, float upper, float margin) {
  GridBox box;
  const size_t n = dynamic_set.size();
  if (n == 0) return box;
  std::vector<float> axis(n);
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < n; ++i) axis[i] = dynamic_set.positions[3 * i + a];
    auto at = [&](float q) {
      size_t k = std::min(n - 1, static_cast<size_t>(q * static_cast<float>(n - 1) + 0.5f));
      std::nth_element(axis.begin(), axis.begin() + k, axis.end());
      return axis[k];
    };
    float lo = at(lower), hi = at(upper);
    float extent = std::max(hi - lo, 1e-3f);
    lo -= margin * extent;
    extent *= 1.0f + 2.0f * margin;
    box.min[a] = lo;
    box.scale[a] = 1.0f / extent;
  }
  return box;
}

}  // namespace m4d
