// NumPy .npy arrays: the header ("descr", "fortran_order", "shape") parsed with limits and
// the data of a little-endian float32 or float64 array in C order, as double.
#ifndef M4D_ENCODER_DATASET_NPY_ARRAY_H_
#define M4D_ENCODER_DATASET_NPY_ARRAY_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// Largest .npy file read (and largest array in an .npz): 1 GiB.
constexpr size_t kMaxNpyBytes = size_t{1} << 30;

struct NpyArray {
  std::vector<size_t> shape;   // empty for a scalar
  std::vector<double> values;  // C order, product of shape values

  double at(size_t row, size_t column) const { return values[row * shape[1] + column]; }
};

// Parses a whole .npy file (format versions 1 to 3). M4D_ERR_UNSUPPORTED for other dtypes
// (only '<f4' and '<f8') or Fortran order, M4D_ERR_BITSTREAM for a malformed header or a
// data size that does not match the shape, M4D_ERR_LIMIT beyond 8 dimensions.
Status ParseNpy(const uint8_t* data, size_t size, NpyArray* array);
Status ReadNpyFile(const std::string& path, NpyArray* array);

// Writes a version 1.0 .npy of float64 ('<f8') values in C order; values.size() must be
// the product of shape.
Status EncodeNpy(const std::vector<size_t>& shape, const std::vector<double>& values,
                 std::vector<uint8_t>* bytes);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_NPY_ARRAY_H_
