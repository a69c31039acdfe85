// No tool replaces a file the user already has unless told to: every output is checked here
// before any work, with one message for every tool.
#ifndef M4D_TOOLS_EXISTING_OUTPUT_H_
#define M4D_TOOLS_EXISTING_OUTPUT_H_

#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>

#include "sdk/src/common/status.h"

namespace m4d {

// An error when the file `path` exists and `force` is false (--force replaces it). A folder
// there is left to the write, whose I/O error says so.
inline Status RefuseExistingOutput(const std::string& path, bool force) {
  std::error_code ec;
  if (force || !std::filesystem::is_regular_file(path, ec)) return Status::Ok();
  return Status(M4D_ERR_INVALID_ARG, path + " exists: give --force to replace it");
}

// An error when `dir` holds a file `frame_<index>.<extension>` with index in [first, last]
// and `force` is false: a tool that writes one file per frame refuses before the first.
inline Status RefuseExistingFrames(const std::string& dir, const std::string& extension,
                                   uint32_t first, uint32_t last, bool force) {
  std::error_code ec;
  if (force || !std::filesystem::is_directory(dir, ec)) return Status::Ok();
  const std::string prefix = "frame_", suffix = "." + extension;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
      continue;
    }
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 10) {
      continue;
    }
    const uint64_t index = std::stoull(digits);
    if (index >= first && index <= last) return RefuseExistingOutput(entry.path().string(), false);
  }
  return Status::Ok();
}

}  // namespace m4d

#endif  // M4D_TOOLS_EXISTING_OUTPUT_H_
