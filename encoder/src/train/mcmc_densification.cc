#include "encoder/src/train/mcmc_densification.h"

#include <algorithm>
#include <cmath>

namespace m4d {
namespace {

float Sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }
float Logit(float p) { return std::log(p / (1.0f - p)); }

// Binomial coefficients C(n, k) for n, k < kMaxRelocationCopies.
struct Binomials {
  double c[kMaxRelocationCopies][kMaxRelocationCopies] = {};
  Binomials() {
    for (int n = 0; n < kMaxRelocationCopies; ++n) {
      c[n][0] = 1;
      for (int k = 1; k <= n; ++k) c[n][k] = c[n - 1][k - 1] + (k < n ? c[n - 1][k] : 0);
    }
  }
};

// `count` rows drawn with replacement from rows [first, n) in proportion to their opacity,
// those with opacity <= min_opacity excluded when `alive_only`.
std::vector<uint32_t> SampleByOpacity(const GaussianModel& model, size_t first, size_t count,
                                      bool alive_only, float min_opacity, TrainingRandom* rng) {
  std::vector<uint32_t> rows;
  std::vector<double> cumulative;
  double total = 0;
  for (size_t i = first; i < model.size(); ++i) {
    const float o = Sigmoid(model.opacity_logits[i]);
    if (!(o > 0.0f) || (alive_only && !(o > min_opacity))) continue;
    total += o;
    rows.push_back(static_cast<uint32_t>(i));
    cumulative.push_back(total);
  }
  std::vector<uint32_t> sampled;
  if (rows.empty()) return sampled;
  sampled.reserve(count);
  for (size_t s = 0; s < count; ++s) {
    const double u = rng->Uniform() * total;
    const size_t k = static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), u) -
                                         cumulative.begin());
    sampled.push_back(rows[std::min(k, rows.size() - 1)]);
  }
  return sampled;
}

}  // namespace

void RelocatedOpacityScale(float opacity, int copies, float* new_opacity, float* scale_factor) {
  static const Binomials binomials;
  const int n = std::clamp(copies, 1, kMaxRelocationCopies);
  const double o = opacity;
  const double shared = 1.0 - std::pow(1.0 - o, 1.0 / n);
  double denominator = 0;
  for (int i = 1; i <= n; ++i) {
    for (int k = 0; k <= i - 1; ++k) {
      const double sign = (k % 2 == 0) ? 1.0 : -1.0;
      denominator += binomials.c[i - 1][k] * sign * std::pow(shared, k + 1) / std::sqrt(k + 1.0);
    }
  }
  *new_opacity = static_cast<float>(shared);
  *scale_factor = denominator > 0 ? static_cast<float>(o / denominator) : 1.0f;
}

void ShareSources(const std::vector<uint32_t>& sources, GaussianModel* model,
                  AdamOptimizer* optimizer) {
  std::vector<uint32_t> distinct = sources;
  std::sort(distinct.begin(), distinct.end());
  std::vector<uint32_t> touched;
  for (size_t a = 0; a < distinct.size();) {
    size_t b = a;
    while (b < distinct.size() && distinct[b] == distinct[a]) ++b;
    const uint32_t row = distinct[a];
    float opacity = 0, factor = 1;
    RelocatedOpacityScale(Sigmoid(model->opacity_logits[row]), static_cast<int>(b - a) + 1,
                          &opacity, &factor);
    constexpr float kMaxOpacity = 1.0f - 1.1920929e-7f;  // float epsilon below one
    model->opacity_logits[row] = Logit(std::min(opacity, kMaxOpacity));
    const float log_factor = std::log(factor);
    for (int axis = 0; axis < 3; ++axis) model->log_scales[3 * size_t{row} + axis] += log_factor;
    touched.push_back(row);
    a = b;
  }
  optimizer->ZeroRows(touched);
}

size_t McmcDensification::Relocate(const StrategyState& state) {
  GaussianModel* model = state.model;
  std::vector<uint32_t> dead;
  for (size_t i = settings_.frozen; i < model->size(); ++i) {
    const float o = Sigmoid(model->opacity_logits[i]);
    if (!(o > settings_.min_opacity)) dead.push_back(static_cast<uint32_t>(i));
  }
  if (dead.empty()) return 0;
  const std::vector<uint32_t> sources = SampleByOpacity(*model, settings_.frozen, dead.size(), true,
                                                        settings_.min_opacity, state.rng);
  if (sources.empty()) return 0;  // nothing opaque to move onto
  ShareSources(sources, model, state.optimizer);
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    const size_t width = static_cast<size_t>(model->width(param));
    std::vector<float>& v = model->values(param);
    for (size_t d = 0; d < dead.size(); ++d) {
      std::copy_n(v.begin() + static_cast<std::ptrdiff_t>(sources[d] * width), width,
                  v.begin() + static_cast<std::ptrdiff_t>(dead[d] * width));
    }
  }
  state.optimizer->ZeroRows(dead);
  return dead.size();
}

size_t McmcDensification::Grow(const StrategyState& state) {
  GaussianModel* model = state.model;
  const size_t n = model->size();
  const size_t target =
      std::min(settings_.max_gaussians,
               static_cast<size_t>(std::floor((1.0 + static_cast<double>(settings_.growth)) * n)));
  if (target <= n) return 0;
  const std::vector<uint32_t> sources = SampleByOpacity(*model, settings_.frozen, target - n, false,
                                                        settings_.min_opacity, state.rng);
  if (sources.empty()) return 0;
  ShareSources(sources, model, state.optimizer);
  model->AppendCopies(sources);
  state.optimizer->AppendZeroRows(sources.size());
  return sources.size();
}

Status McmcDensification::AfterBackward(const StrategyStep& step, const StrategyState& state,
                                        StrategyOutcome* outcome) {
  *outcome = StrategyOutcome();
  outcome->before = state.model->size();
  const int it = step.iteration;
  const McmcSettings& s = settings_;
  if (it <= s.refine_from || it >= s.refine_until || s.refine_interval <= 0 ||
      it % s.refine_interval != 0) {
    return Status::Ok();
  }
  const size_t relocated = Relocate(state);
  const size_t added = Grow(state);
  counts_.relocated += relocated;
  counts_.added += added;
  outcome->rows_changed = relocated + added > 0;
  return Status::Ok();
}

void McmcDensification::Regularize(const GaussianModel& model, GaussianModel* gradients) const {
  const size_t n = model.size();
  if (n == 0) return;
  const float opacity_weight = settings_.opacity_regularization / static_cast<float>(n);
  const float scale_weight = settings_.scale_regularization / static_cast<float>(3 * n);
  for (size_t i = settings_.frozen; i < n; ++i) {
    const float o = Sigmoid(model.opacity_logits[i]);
    gradients->opacity_logits[i] += opacity_weight * o * (1.0f - o);
    for (int a = 0; a < 3; ++a) {
      gradients->log_scales[3 * i + a] += scale_weight * std::exp(model.log_scales[3 * i + a]);
    }
  }
}

void McmcDensification::AfterStep(const StrategyStep& step, const StrategyState& state) {
  GaussianModel* model = state.model;
  const float rate = settings_.noise_learning_rate * step.position_learning_rate;
  for (size_t i = settings_.frozen; i < model->size(); ++i) {
    const float o = Sigmoid(model->opacity_logits[i]);
    // The paper's sigmoid with k = 100 and x0 = 0.995: only the nearly transparent move.
    const float gate = Sigmoid(100.0f * ((1.0f - o) - 0.995f));
    const float amount = gate * rate;
    if (!(amount > 1e-12f)) continue;
    float r[9];
    QuaternionMatrix(&model->rotations[4 * i], r);
    float n[3] = {state.rng->Normal(), state.rng->Normal(), state.rng->Normal()};
    // Sigma n = R S^2 R^T n.
    float local[3];
    for (int a = 0; a < 3; ++a) {
      const float s = std::exp(model->log_scales[3 * i + a]);
      local[a] = s * s * (r[a] * n[0] + r[3 + a] * n[1] + r[6 + a] * n[2]);
    }
    for (int a = 0; a < 3; ++a) {
      model->positions[3 * i + a] +=
          amount * (r[3 * a] * local[0] + r[3 * a + 1] * local[1] + r[3 * a + 2] * local[2]);
    }
  }
}

}  // namespace m4d
