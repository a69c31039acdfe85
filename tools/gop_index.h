// The GOP index of an M4D stream: where each GOP starts, how many frames and bytes it holds
// and whether a decoder may start there (a SEQUENCE_HEADER), for players that fetch by GOP.
#ifndef M4D_TOOLS_GOP_INDEX_H_
#define M4D_TOOLS_GOP_INDEX_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"

namespace m4d {

struct GopEntry {
  int64_t frame = 0;           // its first frame's index
  int64_t frames = 0;          // frames in the GOP
  uint64_t offset = 0;         // byte offset of its first packet
  uint64_t bytes = 0;          // its bytes
  bool random_access = false;  // it starts with a SEQUENCE_HEADER
};

struct GopIndex {
  uint64_t stream_bytes = 0;
  int64_t frames = 0;
  double fps = 0;
  std::vector<GopEntry> gops;
};

// Lists the GOPs of a whole stream held in memory; an error (with a message) for a damaged
// stream.
Status BuildGopIndex(const uint8_t* data, size_t size, GopIndex* index);

// The JSON text of the index (format, version, stream_bytes, frames, fps, gops).
std::string GopIndexJson(const GopIndex& index);

}  // namespace m4d

#endif  // M4D_TOOLS_GOP_INDEX_H_
