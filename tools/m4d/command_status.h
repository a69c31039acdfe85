// How m4d commands end: a Status becomes a message on stderr and an exit code.
#ifndef M4D_TOOLS_M4D_COMMAND_STATUS_H_
#define M4D_TOOLS_M4D_COMMAND_STATUS_H_

#include <cstdio>

#include "sdk/src/common/status.h"

namespace m4d {

// 0 for OK; otherwise prints "m4d <command>: <message>" and returns 1. The error's name is
// added where it says something about the data (an invalid bitstream, a limit); an invalid
// argument's or an I/O error's message says what went wrong by itself.
inline int ReportStatus(const char* command, const Status& status) {
  if (status.ok()) return 0;
  if (status.code() == M4D_ERR_INVALID_ARG) {
    std::fprintf(stderr, "m4d %s: %s\n", command, status.message().c_str());
  } else {
    std::fprintf(stderr, "m4d %s: %s (%s)\n", command, status.message().c_str(),
                 m4d_error_string(status.code()));
  }
  return 1;
}

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_COMMAND_STATUS_H_
