// The learned entropy model of the motion grid (paper section 4.2): a factorized prior whose
// CDF is a learned mixture of logistics, one per (level, channel). The probability of a
// quantized value y is CDF(y + 1/2) - CDF(y - 1/2) (paper eq. pmf_from_cdf) and its rate is
// -log2 of that. It only shapes training; the stream carries a histogram of the actual
// values instead (paper section 5.1), so none of these parameters is transmitted.
#ifndef M4D_ENCODER_MOTION_LOGISTIC_ENTROPY_MODEL_H_
#define M4D_ENCODER_MOTION_LOGISTIC_ENTROPY_MODEL_H_

#include <cstddef>
#include <vector>

namespace m4d {

class LogisticEntropyModel {
 public:
  static constexpr int kComponents = 3;
  // Per distribution: kComponents mixture logits, means, log scales.
  static constexpr int kParameters = 3 * kComponents;

  // `distributions` independent densities, each initialised as a peak at zero of width
  // `initial_scale` with wider shoulders.
  explicit LogisticEntropyModel(int distributions = 0, float initial_scale = 0.5f);

  int distributions() const { return static_cast<int>(params_.size() / kParameters); }
  std::vector<float>& parameters() { return params_; }
  const std::vector<float>& parameters() const { return params_; }

  // Bits of the values y[0..count) (stride apart) under distribution d. When d_y is not null,
  // adds scale * dBits/dy[i] into d_y[i * stride]; when d_params is not null, adds
  // scale * dBits/dparams into d_params (shaped like parameters()).
  double Bits(int d, const float* y, size_t count, size_t stride, float scale, float* d_y,
              float* d_params) const;

 private:
  std::vector<float> params_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_LOGISTIC_ENTROPY_MODEL_H_
