// libFuzzer target for the .npy reader: the input is a .npy file (or anything else). Parsing
// must fail cleanly or give as many values as the shape says.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "encoder/src/dataset/npy_array.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  m4d::NpyArray array;
  if (!m4d::ParseNpy(data, size, &array).ok()) return 0;
  size_t count = 1;
  for (size_t dimension : array.shape) count *= dimension;
  if (count != array.values.size()) std::abort();
  return 0;
}
