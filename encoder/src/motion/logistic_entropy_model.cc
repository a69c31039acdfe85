#include "encoder/src/motion/logistic_entropy_model.h"

#include <algorithm>
#include <cmath>

namespace m4d {
namespace {

constexpr double kMinProbability = 1e-9;  // keeps the rate finite for outliers
constexpr double kLn2 = 0.69314718055994530942;

// A component's bin edges are 1 / s apart in z, so exp(-z_low) = exp(-z_high) * exp(1 / s):
// one exp per component and value instead of two (the rate was a seventh of a motion step).
// Beyond kMaxSharedInvScale the product could overflow, and each edge takes its own exp.
constexpr double kMaxSharedInvScale = 30.0;
constexpr double kMaxExpArgument = 600.0;  // sigmoid(-600) is 0 for every sum below

double Sigmoid(double z) { return 1.0 / (1.0 + std::exp(-z)); }

}  // namespace

LogisticEntropyModel::LogisticEntropyModel(int distributions, float initial_scale)
    : params_(static_cast<size_t>(distributions) * kParameters) {
  const float widths[kComponents] = {1.0f, 4.0f, 16.0f};
  for (int d = 0; d < distributions; ++d) {
    float* p = &params_[static_cast<size_t>(d) * kParameters];
    for (int k = 0; k < kComponents; ++k) {
      p[k] = k == 0 ? 2.0f : 0.0f;  // most mass in the narrow peak
      p[kComponents + k] = 0.0f;
      p[2 * kComponents + k] = std::log(initial_scale * widths[k]);
    }
  }
}

double LogisticEntropyModel::Bits(int d, const float* y, size_t count, size_t stride, float scale,
                                  float* d_y, float* d_params) const {
  const float* p = &params_[static_cast<size_t>(d) * kParameters];
  double weight[kComponents], mean[kComponents], inv_s[kComponents], edge_ratio[kComponents];
  double max_logit = *std::max_element(p, p + kComponents);
  double norm = 0;
  for (int k = 0; k < kComponents; ++k) {
    weight[k] = std::exp(p[k] - max_logit);
    norm += weight[k];
    mean[k] = p[kComponents + k];
    inv_s[k] = std::exp(-p[2 * kComponents + k]);
    edge_ratio[k] = inv_s[k] <= kMaxSharedInvScale ? std::exp(inv_s[k]) : 0.0;
  }
  for (double& w : weight) w /= norm;

  double bits = 0;
  double g_logit[kComponents] = {}, g_mean[kComponents] = {}, g_log_s[kComponents] = {};
  for (size_t i = 0; i < count; ++i) {
    const double v = y[i * stride];
    double prob = 0, dprob_dy = 0;
    double comp[kComponents], dcomp_dmean[kComponents], dcomp_dlogs[kComponents];
    for (int k = 0; k < kComponents; ++k) {
      const double zh = (v + 0.5 - mean[k]) * inv_s[k], zl = (v - 0.5 - mean[k]) * inv_s[k];
      double sh, sl;
      if (edge_ratio[k] > 0.0) {
        const double eh = std::exp(std::min(-zh, kMaxExpArgument));
        sh = 1.0 / (1.0 + eh);
        sl = 1.0 / (1.0 + eh * edge_ratio[k]);
      } else {
        sh = Sigmoid(zh);
        sl = Sigmoid(zl);
      }
      const double ph = sh * (1 - sh), pl = sl * (1 - sl);  // dsigma/dz
      comp[k] = sh - sl;
      dcomp_dmean[k] = -(ph - pl) * inv_s[k];
      dcomp_dlogs[k] = -(ph * zh - pl * zl);
      prob += weight[k] * comp[k];
      dprob_dy += weight[k] * (ph - pl) * inv_s[k];
    }
    const bool floored = prob < kMinProbability;
    const double q = floored ? kMinProbability : prob;
    bits -= std::log(q) / kLn2;
    if (floored) continue;  // constant there: no gradient
    const double dbits_dprob = -scale / (q * kLn2);
    if (d_y) d_y[i * stride] += static_cast<float>(dbits_dprob * dprob_dy);
    if (d_params) {
      for (int k = 0; k < kComponents; ++k) {
        g_logit[k] += dbits_dprob * weight[k] * (comp[k] - prob);  // softmax
        g_mean[k] += dbits_dprob * weight[k] * dcomp_dmean[k];
        g_log_s[k] += dbits_dprob * weight[k] * dcomp_dlogs[k];
      }
    }
  }
  if (d_params) {
    float* g = d_params + static_cast<size_t>(d) * kParameters;
    for (int k = 0; k < kComponents; ++k) {
      g[k] += static_cast<float>(g_logit[k]);
      g[kComponents + k] += static_cast<float>(g_mean[k]);
      g[2 * kComponents + k] += static_cast<float>(g_log_s[k]);
    }
  }
  return bits;
}

}  // namespace m4d
