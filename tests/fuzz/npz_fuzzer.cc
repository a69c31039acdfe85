// libFuzzer target for the zip reader behind .npz archives: the input is an archive (or
// anything else); the entry "data.npy" is extracted (64 KiB limit) and parsed. Reading must
// fail cleanly or respect the limit.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "encoder/src/dataset/npz_archive.h"
#include "encoder/src/dataset/zip_archive.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  constexpr size_t kLimit = 1 << 16;
  std::vector<uint8_t> entry;
  if (m4d::ReadZipEntry(data, size, "data.npy", kLimit, &entry).ok() && entry.size() > kLimit) {
    std::abort();
  }
  m4d::NpyArray array;
  (void)m4d::ParseNpzArray(data, size, "data", &array);
  return 0;
}
