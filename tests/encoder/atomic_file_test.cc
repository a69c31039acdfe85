// Outputs are written whole or not at all, and output paths are checked before work.
#include "encoder/src/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "encoder/src/image_io/file_bytes.h"
#include "tests/encoder/image_test_util.h"

namespace m4d {
namespace {

std::vector<uint8_t> Read(const std::string& path) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(ReadFileBytes(path, 1 << 20, &bytes).ok());
  return bytes;
}

// Files in `dir` other than `keep`: what a failed or finished write left behind.
size_t StrayFiles(const std::string& dir, const std::string& keep) {
  size_t stray = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    stray += entry.path().filename() != keep;
  }
  return stray;
}

TEST(AtomicFile, ReplacesWholeAndLeavesNothingBehind) {
  const std::string dir = testing::TempPath("dir");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/out.bin";
  const std::vector<uint8_t> first = {1, 2, 3}, second = {9, 8, 7, 6, 5};
  ASSERT_TRUE(WriteFileAtomically(path, first.data(), first.size()).ok());
  EXPECT_EQ(Read(path), first);
  ASSERT_TRUE(WriteFileAtomically(path, second.data(), second.size()).ok());
  EXPECT_EQ(Read(path), second);
  EXPECT_EQ(StrayFiles(dir, "out.bin"), 0u);
  std::filesystem::remove_all(dir);
}

TEST(AtomicFile, AFailedWriteNamesThePathAndChangesNothing) {
  const std::string dir = testing::TempPath("dir");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/target");  // a directory where the file would go
  const std::vector<uint8_t> bytes = {1};
  const Status status = WriteFileAtomically(dir + "/target", bytes.data(), bytes.size());
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_NE(status.message().find(dir + "/target"), std::string::npos) << status.message();
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/target"));
  EXPECT_EQ(StrayFiles(dir, "target"), 0u);
  EXPECT_EQ(WriteFileAtomically(dir + "/missing/out.bin", bytes.data(), 1).code(),
            M4D_ERR_INVALID_ARG);
  std::filesystem::remove_all(dir);
}

TEST(AtomicFile, CheckOutputPathCreatesTheDirectoryAndRefusesADirectory) {
  const std::string dir = testing::TempPath("dir");
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(CheckOutputPath(dir + "/a/b/out.m4d").ok());
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/a/b"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/a/b/out.m4d"));  // nothing written
  EXPECT_EQ(StrayFiles(dir + "/a/b", ""), 0u);
  EXPECT_EQ(CheckOutputPath(dir + "/a").code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(CheckOutputPath("/proc/m4d_cannot_write_here/out.m4d").code(), M4D_ERR_INVALID_ARG);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace m4d
