// The GOP index of a stream: where each GOP starts (byte offset, first frame), how many bytes
// and frames it holds and whether decoding can start there. A player that streams over HTTP
// fetches whole GOPs with range requests from it; m4d_probe --gop-index writes it as a sidecar
// (STREAM.m4d.gops.json) and m4d encode beside its renditions.
#ifndef M4D_ENCODER_STREAM_GOP_INDEX_H_
#define M4D_ENCODER_STREAM_GOP_INDEX_H_

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

struct GopEntry {
  int64_t frame = 0;           // frame_index of its keyframe
  int64_t frames = 0;          // frames in the GOP
  uint64_t offset = 0;         // byte offset of its first packet
  uint64_t bytes = 0;          // its bytes: up to the next GOP's offset or the end of the stream
  bool random_access = false;  // its keyframe starts with a SEQUENCE_HEADER
};

struct GopIndex {
  uint64_t stream_bytes = 0;
  int64_t frames = 0;  // frames in the stream
  double fps = 0;      // as the stream's SEQUENCE_HEADER declares it
  std::vector<GopEntry> gops;
};

// Lists the GOPs of a whole stream held in memory; an error (with a message) for a damaged stream.
// The packets are split with m4d_parse_packet_header and every packet is decoded, so a damaged
// payload, a truncated stream or one that does not start at a random-access keyframe is an
// error naming the byte where it was found; *index is then left empty.
Status BuildGopIndex(const uint8_t* data, size_t size, GopIndex* index);

// The "gops" array of the JSON below: one object per GOP, its fields in GopEntry's order. The
// rendition manifest embeds it too, so both files describe a GOP alike.
nlohmann::ordered_json GopsJson(const std::vector<GopEntry>& gops);

// The JSON text above (format, version, stream_bytes, frames, fps, gops).
std::string GopIndexJson(const GopIndex& index);

}  // namespace m4d

#endif  // M4D_ENCODER_STREAM_GOP_INDEX_H_
