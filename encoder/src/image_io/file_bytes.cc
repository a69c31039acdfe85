#include "encoder/src/image_io/file_bytes.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "encoder/src/io/atomic_file.h"

namespace m4d {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

Status IoError(const std::string& what, const std::string& path) {
  // The public error codes have none for I/O; the message says it.
  return Status(M4D_ERR_INVALID_ARG,
                "cannot " + what + " '" + path + "': " + std::strerror(errno) + " (I/O error)");
}

}  // namespace

Status ReadFileBytes(const std::string& path, size_t max_bytes, std::vector<uint8_t>* bytes) {
  errno = 0;
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) return IoError("open", path);
  bytes->clear();
  constexpr size_t kChunk = size_t{1} << 16;
  while (true) {
    const size_t old_size = bytes->size();
    // One byte past the limit is enough to tell that the file is too large.
    const size_t want = std::min(kChunk, max_bytes - old_size + (max_bytes < SIZE_MAX));
    bytes->resize(old_size + want);
    const size_t got = std::fread(bytes->data() + old_size, 1, want, file.get());
    bytes->resize(old_size + got);
    if (bytes->size() > max_bytes) {
      bytes->clear();
      return LimitError("'" + path + "' is larger than " + std::to_string(max_bytes) + " bytes");
    }
    if (got < want) break;
  }
  if (std::ferror(file.get())) return IoError("read", path);
  return Status::Ok();
}

Status DecodeImageFile(const std::string& path, ImageDecoder decode, Image* image) {
  std::vector<uint8_t> bytes;
  Status status = ReadFileBytes(path, kMaxImageBytes, &bytes);
  if (status.ok()) status = decode(bytes.data(), bytes.size(), image);
  if (status.ok()) return status;
  return Status(status.code(), status.message() + " (" + path + ")");
}

Status WriteFileBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  return WriteFileAtomically(path, bytes.data(), bytes.size());
}

}  // namespace m4d
