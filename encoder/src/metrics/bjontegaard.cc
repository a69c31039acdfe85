#include "encoder/src/metrics/bjontegaard.h"

#include <algorithm>
#include <cmath>

namespace m4d {
namespace {

// y(x) through the points by PCHIP.
class Pchip {
 public:
  Pchip(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
    const size_t n = x_.size();
    std::vector<double> h(n - 1), delta(n - 1);
    for (size_t k = 0; k + 1 < n; ++k) {
      h[k] = x_[k + 1] - x_[k];
      delta[k] = (y_[k + 1] - y_[k]) / h[k];
    }
    slope_.assign(n, 0.0);
    if (n == 2) {
      slope_[0] = slope_[1] = delta[0];
      return;
    }
    // Interior: weighted harmonic mean of the neighbouring secants, 0 at extrema.
    for (size_t k = 1; k + 1 < n; ++k) {
      if (delta[k - 1] * delta[k] <= 0) continue;
      const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
      slope_[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k]);
    }
    slope_[0] = EndSlope(h[0], h[1], delta[0], delta[1]);
    slope_[n - 1] = EndSlope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
  }

  // The integral of y over [lo, hi], inside the points' range.
  double Integral(double lo, double hi) const {
    double sum = 0;
    for (size_t k = 0; k + 1 < x_.size(); ++k) {
      const double a = std::max(lo, x_[k]), b = std::min(hi, x_[k + 1]);
      if (a >= b) continue;
      const double h = x_[k + 1] - x_[k];
      sum += h * (Antiderivative(k, (b - x_[k]) / h) - Antiderivative(k, (a - x_[k]) / h));
    }
    return sum;
  }

 private:
  // The three-point end slope, kept monotone (as SciPy's and MATLAB's pchip).
  static double EndSlope(double h0, double h1, double d0, double d1) {
    double d = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (d * d0 <= 0) return 0;
    if (d0 * d1 <= 0 && std::fabs(d) > std::fabs(3 * d0)) d = 3 * d0;
    return d;
  }

  // Integral over [0, t] of segment k's Hermite cubic in its unit parameter (times 1 / h).
  double Antiderivative(size_t k, double t) const {
    const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
    const double h = x_[k + 1] - x_[k];
    const double h00 = t4 / 2 - t3 + t, h10 = t4 / 4 - 2 * t3 / 3 + t2 / 2;
    const double h01 = -t4 / 2 + t3, h11 = t4 / 4 - t3 / 3;
    return h00 * y_[k] + h10 * h * slope_[k] + h01 * y_[k + 1] + h11 * h * slope_[k + 1];
  }

  std::vector<double> x_, y_, slope_;
};

Status CheckCurve(std::vector<RatePoint>* curve, const char* name) {
  auto bad = [name](const char* why) {
    return Status(M4D_ERR_INVALID_ARG, std::string("Bjontegaard: ") + name + " curve " + why);
  };
  if (curve->size() < 2) return bad("needs at least two points");
  for (const RatePoint& p : *curve) {
    if (!(p.rate > 0) || !std::isfinite(p.rate) || !std::isfinite(p.psnr)) {
      return bad("has a rate <= 0 or a non-finite value");
    }
  }
  std::sort(curve->begin(), curve->end(),
            [](const RatePoint& a, const RatePoint& b) { return a.rate < b.rate; });
  for (size_t k = 1; k < curve->size(); ++k) {
    if (!((*curve)[k].rate > (*curve)[k - 1].rate) || !((*curve)[k].psnr > (*curve)[k - 1].psnr)) {
      return bad("is not strictly increasing in rate and PSNR");
    }
  }
  return Status::Ok();
}

// Mean over the common x range of test(x) - anchor(x), each curve given as y over x; false
// when the ranges do not overlap.
bool MeanDifference(const std::vector<double>& ax, const std::vector<double>& ay,
                    const std::vector<double>& tx, const std::vector<double>& ty, double* mean) {
  const double lo = std::max(ax.front(), tx.front()), hi = std::min(ax.back(), tx.back());
  if (!(hi > lo)) return false;
  *mean = (Pchip(tx, ty).Integral(lo, hi) - Pchip(ax, ay).Integral(lo, hi)) / (hi - lo);
  return true;
}

}  // namespace

Status ComputeBjontegaard(std::vector<RatePoint> anchor, std::vector<RatePoint> test,
                          BjontegaardDelta* delta) {
  M4D_RETURN_IF_ERROR(CheckCurve(&anchor, "anchor"));
  M4D_RETURN_IF_ERROR(CheckCurve(&test, "test"));
  std::vector<double> a_log, a_psnr, t_log, t_psnr;
  for (const RatePoint& p : anchor) {
    a_log.push_back(std::log10(p.rate));
    a_psnr.push_back(p.psnr);
  }
  for (const RatePoint& p : test) {
    t_log.push_back(std::log10(p.rate));
    t_psnr.push_back(p.psnr);
  }
  *delta = BjontegaardDelta();
  double log_rate_difference = 0;
  delta->has_rate = MeanDifference(a_psnr, a_log, t_psnr, t_log, &log_rate_difference);
  if (delta->has_rate) delta->rate_percent = (std::pow(10.0, log_rate_difference) - 1.0) * 100.0;
  delta->has_psnr = MeanDifference(a_log, a_psnr, t_log, t_psnr, &delta->psnr_db);
  if (!delta->has_rate && !delta->has_psnr) {
    return Status(M4D_ERR_INVALID_ARG, "Bjontegaard: the curves share no rate or PSNR range");
  }
  return Status::Ok();
}

}  // namespace m4d
