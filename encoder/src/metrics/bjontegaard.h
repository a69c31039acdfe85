// Bjontegaard delta rate and delta PSNR between two rate-distortion curves, with the
// piecewise cubic Hermite interpolation (PCHIP, Fritsch-Carlson slopes) that VCEG and JVET's
// reporting templates use instead of Bjontegaard's original cubic polynomial fit.
//
// BD-rate: log10(rate) as a function of PSNR for each curve, integrated over the PSNR range
// both cover; the mean difference d (test minus anchor) gives (10^d - 1) * 100, the percent
// of rate the test curve needs for the same quality (negative: it saves). BD-PSNR: PSNR as a
// function of log10(rate), over the common log-rate range; the mean difference in dB.
#ifndef M4D_ENCODER_METRICS_BJONTEGAARD_H_
#define M4D_ENCODER_METRICS_BJONTEGAARD_H_

#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

struct RatePoint {
  double rate = 0;  // any unit (bytes, kbit/s), the same on both curves; > 0
  double psnr = 0;  // dB
};

struct BjontegaardDelta {
  bool has_rate = false;    // the curves share a PSNR range
  double rate_percent = 0;  // BD-rate of test against anchor
  bool has_psnr = false;    // the curves share a rate range
  double psnr_db = 0;       // BD-PSNR of test against anchor
};

// Each curve needs at least two points with positive, finite rates and finite PSNRs, rate and
// PSNR both strictly increasing once sorted by rate. Each delta needs its common range (a
// codec much cheaper than the anchor at the same quality has a BD-rate but no BD-PSNR); when
// neither range is shared, or a curve is unusable, M4D_ERR_INVALID_ARG.
Status ComputeBjontegaard(std::vector<RatePoint> anchor, std::vector<RatePoint> test,
                          BjontegaardDelta* delta);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_BJONTEGAARD_H_
