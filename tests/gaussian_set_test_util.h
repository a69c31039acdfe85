// Helpers shared by the gaussian_set() coding tests.
#ifndef M4D_TESTS_GAUSSIAN_SET_TEST_UTIL_H_
#define M4D_TESTS_GAUSSIAN_SET_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "common/byte_writer.h"
#include "layers/gaussian_set.h"
#include "layers/gaussian_set_writer.h"

namespace m4d {
namespace testing {

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
