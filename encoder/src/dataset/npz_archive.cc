#include "encoder/src/dataset/npz_archive.h"

#include <vector>

#include "encoder/src/dataset/zip_archive.h"
#include "encoder/src/image_io/file_bytes.h"

namespace m4d {
namespace {

// An .npy entry: the array's limit plus room for its header.
constexpr size_t kMaxEntryBytes = kMaxNpyBytes + (size_t{1} << 20);

}  // namespace

Status ParseNpzArray(const uint8_t* data, size_t size, const std::string& name, NpyArray* array) {
  std::vector<uint8_t> entry;
  M4D_RETURN_IF_ERROR(ReadZipEntry(data, size, name + ".npy", kMaxEntryBytes, &entry));
  return ParseNpy(entry.data(), entry.size(), array);
}

Status ReadNpzArray(const std::string& path, const std::string& name, NpyArray* array) {
  std::vector<uint8_t> bytes;
  Status status = ReadFileBytes(path, kMaxEntryBytes * 2, &bytes);
  if (status.ok()) status = ParseNpzArray(bytes.data(), bytes.size(), name, array);
  if (status.ok()) return status;
  return Status(status.code(), status.message() + " (" + path + ")");
}

}  // namespace m4d
