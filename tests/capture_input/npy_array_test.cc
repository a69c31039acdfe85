// NumPy array files (dataset/npy_array.h, dataset/npz_archive.h): headers as numpy writes
// them, both float types, malformed and oversized headers, and arrays inside .npz archives.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "encoder/src/dataset/npy_array.h"
#include "encoder/src/dataset/npz_archive.h"
#include "tests/capture_input/dataset_test_util.h"

namespace m4d {
namespace {

using testing::MakeZip;
using testing::ZipMethod;

// A .npy file as numpy writes it: magic, version, header length, padded dict, data.
std::vector<uint8_t> Npy(const std::string& dict, const std::vector<uint8_t>& data, int major = 1) {
  std::string header = dict;
  const size_t prefix = 6 + 2 + (major == 1 ? 2 : 4);
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::vector<uint8_t> bytes = {0x93, 'N', 'U', 'M', 'P', 'Y', static_cast<uint8_t>(major), 0};
  for (int i = 0; i < (major == 1 ? 2 : 4); ++i) {
    bytes.push_back(static_cast<uint8_t>(header.size() >> (8 * i)));
  }
  bytes.insert(bytes.end(), header.begin(), header.end());
  bytes.insert(bytes.end(), data.begin(), data.end());
  return bytes;
}

template <typename T>
std::vector<uint8_t> Bytes(const std::vector<T>& values) {
  std::vector<uint8_t> bytes(values.size() * sizeof(T));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

TEST(NpyArrayTest, ParsesBothFloatTypesAndVersions) {
  NpyArray array;
  const std::vector<uint8_t> f8 = Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }",
                                      Bytes(std::vector<double>{1, 2, 3, 4, 5, 6.5}));
  ASSERT_TRUE(ParseNpy(f8.data(), f8.size(), &array).ok());
  EXPECT_EQ(array.shape, (std::vector<size_t>{2, 3}));
  EXPECT_EQ(array.values, (std::vector<double>{1, 2, 3, 4, 5, 6.5}));
  EXPECT_EQ(array.at(1, 2), 6.5);

  const std::vector<uint8_t> f4 = Npy("{'shape': (3,), 'fortran_order': False, 'descr': '<f4'}",
                                      Bytes(std::vector<float>{0.25f, -1, 3}), 2);
  ASSERT_TRUE(ParseNpy(f4.data(), f4.size(), &array).ok());
  EXPECT_EQ(array.shape, (std::vector<size_t>{3}));
  EXPECT_EQ(array.values, (std::vector<double>{0.25, -1, 3}));

  const std::vector<uint8_t> scalar =
      Npy("{'descr': '<f8', 'fortran_order': False, 'shape': ()}", Bytes(std::vector<double>{7}));
  ASSERT_TRUE(ParseNpy(scalar.data(), scalar.size(), &array).ok());
  EXPECT_TRUE(array.shape.empty());
  EXPECT_EQ(array.values, (std::vector<double>{7}));
}

TEST(NpyArrayTest, EncodeRoundTrips) {
  std::vector<uint8_t> bytes;
  const std::vector<double> values = {1, -2, 3.25, 4, 5, 6, 7, 8};
  ASSERT_TRUE(EncodeNpy({2, 4}, values, &bytes).ok());
  EXPECT_EQ(bytes.size() % 64, 0u);  // 64-byte aligned header, 64 bytes of data
  NpyArray array;
  ASSERT_TRUE(ParseNpy(bytes.data(), bytes.size(), &array).ok());
  EXPECT_EQ(array.shape, (std::vector<size_t>{2, 4}));
  EXPECT_EQ(array.values, values);
  ASSERT_TRUE(EncodeNpy({8}, values, &bytes).ok());
  ASSERT_TRUE(ParseNpy(bytes.data(), bytes.size(), &array).ok());
  EXPECT_EQ(array.shape, (std::vector<size_t>{8}));
  EXPECT_EQ(EncodeNpy({3}, values, &bytes).code(), M4D_ERR_INVALID_ARG);
}

TEST(NpyArrayTest, RejectsBadFiles) {
  NpyArray array;
  const std::vector<uint8_t> six = Bytes(std::vector<double>{1, 2, 3, 4, 5, 6});
  auto code = [&array](const std::vector<uint8_t>& bytes) {
    return ParseNpy(bytes.data(), bytes.size(), &array).code();
  };
  EXPECT_EQ(code(Npy("{'descr': '>f8', 'fortran_order': False, 'shape': (6,), }", six)),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(code(Npy("{'descr': '<i8', 'fortran_order': False, 'shape': (6,), }", six)),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", six)),
            M4D_ERR_UNSUPPORTED);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (7,), }", six)),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (5,), }", six)),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'shape': (6,), }", six)), M4D_ERR_BITSTREAM);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (6,) ", six)),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': Maybe, 'shape': (6,)}", six)),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (-6,)}", six)),
            M4D_ERR_BITSTREAM);
  EXPECT_EQ(code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (6,), 'x': 1}", six)),
            M4D_ERR_BITSTREAM);
  // Shapes whose product overflows, or too many dimensions, are limits, not allocations.
  EXPECT_EQ(
      code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (999999999999, 999999999999)}",
               six)),
      M4D_ERR_LIMIT);
  EXPECT_EQ(
      code(Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1,1,1,1,1,1,1,1,6)}", six)),
      M4D_ERR_LIMIT);
  std::vector<uint8_t> bad_magic =
      Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (6,)}", six);
  bad_magic[1] = 'X';
  EXPECT_EQ(code(bad_magic), M4D_ERR_UNSUPPORTED);
  std::vector<uint8_t> version4 =
      Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (6,)}", six);
  version4[6] = 4;
  EXPECT_EQ(code(version4), M4D_ERR_UNSUPPORTED);
  // A header length beyond the file.
  std::vector<uint8_t> cut = Npy("{'descr': '<f8', 'fortran_order': False, 'shape': (6,)}", six);
  cut.resize(20);
  EXPECT_EQ(code(cut), M4D_ERR_BITSTREAM);
  for (size_t n = 0; n < 10; ++n) EXPECT_NE(ParseNpy(cut.data(), n, &array).code(), M4D_OK);
}

TEST(NpyArrayTest, ReadsArraysFromNpzArchives) {
  std::vector<uint8_t> data_npy, other_npy;
  std::vector<double> values(7 * 40);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 0.5 * static_cast<double>(i % 17);
  ASSERT_TRUE(EncodeNpy({40, 7}, values, &data_npy).ok());
  ASSERT_TRUE(EncodeNpy({2}, {1, 2}, &other_npy).ok());
  for (ZipMethod method : {ZipMethod::kStored, ZipMethod::kDeflated,
                           ZipMethod::kDeflatedWithDescriptor, ZipMethod::kStoredZip64}) {
    const std::vector<uint8_t> zip =
        MakeZip({{"other.npy", other_npy}, {"data.npy", data_npy}}, method);
    NpyArray array;
    const Status status = ParseNpzArray(zip.data(), zip.size(), "data", &array);
    ASSERT_TRUE(status.ok()) << status.message() << " method " << static_cast<int>(method);
    EXPECT_EQ(array.shape, (std::vector<size_t>{40, 7}));
    EXPECT_EQ(array.values, values);
    EXPECT_EQ(ParseNpzArray(zip.data(), zip.size(), "missing", &array).code(), M4D_ERR_INVALID_ARG);
  }
}

}  // namespace
}  // namespace m4d
