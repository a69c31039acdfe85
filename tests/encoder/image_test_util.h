// Helpers for image file tests: per-test temporary paths and byte-level edits.
#ifndef M4D_TESTS_ENCODER_IMAGE_TEST_UTIL_H_
#define M4D_TESTS_ENCODER_IMAGE_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "encoder/src/image_io/file_bytes.h"

namespace m4d {
namespace testing {

// A file name in the test temporary directory, unique per test (ctest runs tests in parallel).
inline std::string TempPath(const std::string& name) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + "m4d_" + info->test_suite_name() + "_" + info->name() + "_" + name;
}

// Writes bytes to a temporary file that is removed when the object goes.
class TempFile {
 public:
  TempFile(const std::string& name, const std::vector<uint8_t>& bytes) : path_(TempPath(name)) {
    EXPECT_TRUE(WriteFileBytes(path_, bytes).ok());
  }
  explicit TempFile(const std::string& name) : path_(TempPath(name)) {}
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

inline void PutBigEndian32(uint32_t v, std::vector<uint8_t>* out) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<uint8_t>(v >> shift));
}

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_ENCODER_IMAGE_TEST_UTIL_H_
