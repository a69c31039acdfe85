#include "encoder/src/train/keyframe_rate_term.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace m4d {
namespace {

constexpr double kBitsPerRateUnit = 100000.0;  // lambda_k per 100 kilobits, as lambda_2
constexpr double kCountPrior = 0.5;            // keeps empty levels' rate finite

// A group's components within each row of a model array.
struct RateGroup {
  const std::vector<float>* values;
  std::vector<float>* gradients;
  size_t stride;
  size_t offset;
  size_t components;
  int bits;
  bool zero_level;  // the writer puts a level at exactly zero (higher SH)
};

// The group's bits at one step shared by its components over their whole range (the writer's
// plan, spec 5.4), adding the scaled rate gradient to the rows from `first` on.
double GroupRate(const RateGroup& g, size_t rows, size_t first, double scale) {
  float lo = (*g.values)[g.offset], hi = lo;
  for (size_t i = 0; i < rows; ++i) {
    for (size_t r = 0; r < g.components; ++r) {
      const float v = (*g.values)[i * g.stride + g.offset + r];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  const int levels = 1 << g.bits;
  const double step = (static_cast<double>(hi) - lo) / (levels - 1);
  if (!(step > 0.0)) return 0.0;
  double low = lo;
  if (g.zero_level && lo < 0.0f && hi > 0.0f) low = -std::round(-low / step) * step;
  auto position = [&](float v) { return (static_cast<double>(v) - low) / step; };
  std::vector<double> count(static_cast<size_t>(levels), 0.0);
  for (size_t i = 0; i < rows; ++i) {
    for (size_t r = 0; r < g.components; ++r) {
      const double y = position((*g.values)[i * g.stride + g.offset + r]);
      count[static_cast<size_t>(std::clamp(std::lround(y), 0L, levels - 1L))] += 1.0;
    }
  }
  const double total = static_cast<double>(rows * g.components) + kCountPrior * levels;
  std::vector<double> rate(count.size());  // bits of a value at each level
  double bits = 0.0;
  for (size_t k = 0; k < count.size(); ++k) {
    rate[k] = -std::log2((count[k] + kCountPrior) / total);
    bits += count[k] * rate[k];
  }
  for (size_t i = first; i < rows; ++i) {
    for (size_t r = 0; r < g.components; ++r) {
      const size_t k = i * g.stride + g.offset + r;
      const double y = position((*g.values)[k]);
      const size_t below = static_cast<size_t>(std::clamp(std::floor(y), 0.0, levels - 2.0));
      (*g.gradients)[k] += static_cast<float>(scale * (rate[below + 1] - rate[below]) / step);
    }
  }
  return bits;
}

}  // namespace

double AddKeyframeRateGradients(const GaussianModel& model,
                                const GaussianQuantization& quantization, double lambda_k,
                                size_t first, GaussianModel* gradients) {
  if (!(lambda_k > 0.0) || model.size() == 0) return 0.0;
  const size_t sh = static_cast<size_t>(model.sh_floats());
  const RateGroup groups[] = {
      {&model.log_scales, &gradients->log_scales, 3, 0, 3, quantization.log_scale_bits, false},
      {&model.opacity_logits, &gradients->opacity_logits, 1, 0, 1, quantization.opacity_bits,
       false},
      {&model.sh, &gradients->sh, sh, 0, 3, quantization.sh_dc_bits, false},
      {&model.sh, &gradients->sh, sh, 3, sh - 3, quantization.sh_rest_bits, true},
  };
  const double scale = lambda_k / kBitsPerRateUnit;
  double bits = 0.0;
  for (const RateGroup& group : groups) {
    if (group.components == 0 || group.bits < 1 || group.bits > 16) continue;
    bits += GroupRate(group, model.size(), first, scale);
  }
  return bits;
}

}  // namespace m4d
