#include "encoder/src/io/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace m4d {
namespace {

Status IoError(const std::string& what, const std::string& path, int error) {
  // The public error codes have none for I/O; the message says it.
  return Status(M4D_ERR_INVALID_ARG,
                "cannot " + what + " '" + path + "': " + std::strerror(error) + " (I/O error)");
}

// A name beside the target, unique to this process.
std::string TemporaryName(const std::string& path) {
  return path + ".tmp" + std::to_string(static_cast<long>(getpid()));
}

Status CreateParent(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) return IoError("create the directory of", path, ec.value());
  return Status::Ok();
}

}  // namespace

Status WriteFileAtomically(const std::string& path, const uint8_t* data, size_t size) {
  const std::string temporary = TemporaryName(path);
  errno = 0;
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) return IoError("create", path, errno);
  bool ok = std::fwrite(data, 1, size, file) == size && std::fflush(file) == 0 &&
            fsync(fileno(file)) == 0;
  int error = errno;
  // fclose flushes too; a full disk may only show here.
  if (std::fclose(file) != 0 && ok) ok = false, error = errno;
  if (ok && std::rename(temporary.c_str(), path.c_str()) != 0) ok = false, error = errno;
  if (!ok) {
    std::remove(temporary.c_str());
    return IoError("write", path, error);
  }
  return Status::Ok();
}

Status CheckOutputPath(const std::string& path) {
  M4D_RETURN_IF_ERROR(CreateParent(path));
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return Status(M4D_ERR_INVALID_ARG, "cannot write '" + path + "': it is a directory");
  }
  const std::string temporary = TemporaryName(path);
  errno = 0;
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) return IoError("create", path, errno);
  std::fclose(file);
  std::remove(temporary.c_str());
  return Status::Ok();
}

}  // namespace m4d
