// What every tool answers to --version: its name, the SDK it runs on and the newest bitstream
// version it reads and writes, so that a bug report names all three.
#ifndef M4D_TOOLS_VERSION_LINE_H_
#define M4D_TOOLS_VERSION_LINE_H_

#include <string>

#include "m4d/m4d.h"

namespace m4d {

// "<tool> <version> (libm4d <version>, bitstream <major>.<minor>)", the tool named as run.
inline std::string VersionLine(const char* argv0) {
  std::string name = argv0 != nullptr ? argv0 : "m4d";
  name = name.substr(name.find_last_of('/') + 1);  // npos + 1 is 0: no folder
  const auto number = [](int major, int minor) {
    return std::to_string(major) + "." + std::to_string(minor);
  };
  // The tool's version is the SDK headers' it was built with; m4d_version() the library's
  // that runs it (a shared libm4d may be newer).
  return name + " " + number(M4D_VERSION_MAJOR, M4D_VERSION_MINOR) + "." +
         std::to_string(M4D_VERSION_PATCH) + " (libm4d " + m4d_version() + ", bitstream " +
         number(M4D_BITSTREAM_VERSION_MAJOR, M4D_BITSTREAM_VERSION_MINOR) + ")";
}

}  // namespace m4d

#endif  // M4D_TOOLS_VERSION_LINE_H_
