// Output files written whole or not at all: the bytes go to a temporary file beside the
// target, which is renamed over it only once every byte is on disk, so an interrupted or
// failed write never leaves a truncated output or destroys the previous one.
#ifndef M4D_ENCODER_IO_ATOMIC_FILE_H_
#define M4D_ENCODER_IO_ATOMIC_FILE_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "sdk/src/common/status.h"

namespace m4d {

// Creates or replaces `path` with `size` bytes; its directory must exist. M4D_ERR_INVALID_ARG,
// naming the path and the system's reason, when it cannot be written; the target is then
// unchanged.
Status WriteFileAtomically(const std::string& path, const uint8_t* data, size_t size);

// Checks, before long work, that `path` can be written: its directory exists (it is created
// when missing) and accepts a new file. The same error as WriteFileAtomically otherwise.
Status CheckOutputPath(const std::string& path);

}  // namespace m4d

#endif  // M4D_ENCODER_IO_ATOMIC_FILE_H_
