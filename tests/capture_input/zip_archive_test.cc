// Zip entry reading (dataset/zip_archive.h): stored and deflated entries, data descriptors,
// ZIP64 sizes, CRC checks, limits and corrupt or truncated archives.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/dataset/zip_archive.h"
#include "tests/capture_input/dataset_test_util.h"

namespace m4d {
namespace {

using testing::MakeZip;
using testing::ZipMethod;

std::vector<uint8_t> Contents(size_t n) {
  std::vector<uint8_t> bytes(n);
  for (size_t i = 0; i < n; ++i) bytes[i] = static_cast<uint8_t>((i * 7) % 13 + (i / 100));
  return bytes;
}

constexpr ZipMethod kMethods[] = {ZipMethod::kStored, ZipMethod::kDeflated,
                                  ZipMethod::kDeflatedWithDescriptor, ZipMethod::kStoredZip64};

TEST(ZipArchiveTest, ReadsEveryEntryWithEveryMethod) {
  const std::vector<uint8_t> a = Contents(5000), b = Contents(3), empty;
  for (ZipMethod method : kMethods) {
    const std::vector<uint8_t> zip =
        MakeZip({{"a.bin", a}, {"dir/b.bin", b}, {"e", empty}}, method);
    std::vector<uint8_t> out;
    ASSERT_TRUE(ReadZipEntry(zip.data(), zip.size(), "a.bin", 1 << 20, &out).ok());
    EXPECT_EQ(out, a);
    ASSERT_TRUE(ReadZipEntry(zip.data(), zip.size(), "dir/b.bin", 1 << 20, &out).ok());
    EXPECT_EQ(out, b);
    const Status status = ReadZipEntry(zip.data(), zip.size(), "e", 1 << 20, &out);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(ReadZipEntry(zip.data(), zip.size(), "b.bin", 1 << 20, &out).code(),
              M4D_ERR_INVALID_ARG);
  }
}

TEST(ZipArchiveTest, EnforcesTheSizeLimit) {
  const std::vector<uint8_t> big = Contents(10000);
  for (ZipMethod method : kMethods) {
    const std::vector<uint8_t> zip = MakeZip({{"big", big}}, method);
    std::vector<uint8_t> out;
    EXPECT_EQ(ReadZipEntry(zip.data(), zip.size(), "big", 9999, &out).code(), M4D_ERR_LIMIT);
    EXPECT_TRUE(ReadZipEntry(zip.data(), zip.size(), "big", 10000, &out).ok());
  }
}

TEST(ZipArchiveTest, RejectsCorruptAndTruncatedArchives) {
  const std::vector<uint8_t> contents = Contents(2000);
  for (ZipMethod method : kMethods) {
    const std::vector<uint8_t> zip = MakeZip({{"x", contents}}, method);
    std::vector<uint8_t> out;
    // Every truncation fails with a status (the entry is cut or never reached).
    for (size_t size = 0; size < zip.size() - 22 - 47; ++size) {
      const Status status = ReadZipEntry(zip.data(), size, "x", 1 << 20, &out);
      EXPECT_FALSE(status.ok()) << size;
    }
    // A flipped data byte fails the CRC or the deflate stream.
    std::vector<uint8_t> flipped = zip;
    flipped[30 + 1 + (method == ZipMethod::kStoredZip64 ? 20 : 0) + 100] ^= 0x40;
    EXPECT_EQ(ReadZipEntry(flipped.data(), flipped.size(), "x", 1 << 20, &out).code(),
              M4D_ERR_BITSTREAM);
  }
  // Encrypted entries and unknown methods are unsupported.
  std::vector<uint8_t> zip = MakeZip({{"x", contents}}, ZipMethod::kStored);
  std::vector<uint8_t> out;
  zip[6] |= 1;
  EXPECT_EQ(ReadZipEntry(zip.data(), zip.size(), "x", 1 << 20, &out).code(), M4D_ERR_UNSUPPORTED);
  zip[6] &= ~1;
  zip[8] = 14;  // LZMA
  EXPECT_EQ(ReadZipEntry(zip.data(), zip.size(), "x", 1 << 20, &out).code(), M4D_ERR_UNSUPPORTED);
  // A deflated entry claiming an implausible size is refused before allocating it.
  std::vector<uint8_t> deflated = MakeZip({{"x", contents}}, ZipMethod::kDeflated);
  deflated[22] = deflated[23] = deflated[24] = 0xff;
  deflated[25] = 0x3f;
  EXPECT_EQ(ReadZipEntry(deflated.data(), deflated.size(), "x", size_t{1} << 31, &out).code(),
            M4D_ERR_BITSTREAM);
}

}  // namespace
}  // namespace m4d
