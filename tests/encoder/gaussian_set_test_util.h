// Helpers shared by the gaussian_set() coding tests.
#ifndef M4D_TESTS_ENCODER_GAUSSIAN_SET_TEST_UTIL_H_
#define M4D_TESTS_ENCODER_GAUSSIAN_SET_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {
namespace testing {

// Uniform floats from a fixed seed.
class UniformFloats {
 public:
  explicit UniformFloats(uint32_t seed) : rng_(seed) {}
  float operator()(float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng_);
  }
  uint32_t Next() { return rng_(); }

 private:
  std::mt19937 rng_;
};

// A set of n Gaussians of that SH degree, every value 0.
inline GaussianSet ZeroSet(size_t n, int sh_degree) {
  GaussianSet set;
  set.sh_degree = sh_degree;
  set.Resize(n);
  return set;
}

// The set's gaussian_set() bytes; a writer failure fails the test.
inline std::vector<uint8_t> WriteSet(const GaussianSet& set, const GaussianQuantization& q) {
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  const Status status = WriteGaussianSet(set, q, &w);
  EXPECT_TRUE(status.ok()) << status.message();
  return bytes;
}

// The covariance R diag(exp(2 s)) R^T of Gaussian i (row-major), R of its normalised quaternion.
inline std::array<double, 9> Covariance(const GaussianSet& set, size_t i) {
  const float* q = &set.rotations[4 * i];
  double u[4], norm = 0.0;
  for (int c = 0; c < 4; ++c) norm += double{q[c]} * q[c];
  for (int c = 0; c < 4; ++c) u[c] = q[c] / std::sqrt(norm);
  const double w = u[0], x = u[1], y = u[2], z = u[3];
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                       2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                       2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  std::array<double, 9> c{};
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      for (int k = 0; k < 3; ++k) {
        c[3 * a + b] += r[3 * a + k] * r[3 * b + k] * std::exp(2.0 * set.log_scales[3 * i + k]);
      }
    }
  }
  return c;
}

// |a - b| / |b| in the Frobenius norm.
inline double RelativeDifference(const std::array<double, 9>& a, const std::array<double, 9>& b) {
  double difference = 0.0, norm = 0.0;
  for (size_t k = 0; k < 9; ++k) {
    difference += (a[k] - b[k]) * (a[k] - b[k]);
    norm += b[k] * b[k];
  }
  return std::sqrt(difference / norm);
}

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_ENCODER_GAUSSIAN_SET_TEST_UTIL_H_
