// Helpers shared by the gaussian_set() coding tests.
#ifndef M4D_TESTS_GAUSSIAN_SET_TEST_UTIL_H_
#define M4D_TESTS_GAUSSIAN_SET_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "common/byte_writer.h"
#include "layers/gaussian_set.h"
#include "layers/gaussian_set_writer.h"

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

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_GAUSSIAN_SET_TEST_UTIL_H_
