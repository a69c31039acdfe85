#include "gop_index.h"

#include <m4d/m4d.h>

#include <nlohmann/json.hpp>

namespace m4d {

namespace {

// The frame rate the stream's first SEQUENCE_HEADER declares.
Status StreamFps(const uint8_t* packet, size_t size, double* fps) {
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* raw = nullptr;
  int r = m4d_open(&raw, &settings);
  if (r != M4D_OK) return Status(r, "GOP index: cannot open a decoder");
  r = m4d_send_packet(raw, packet, size);
  M4dStreamInfo info;
  if (r == M4D_OK) r = m4d_get_stream_info(raw, &info);
  m4d_close(&raw);
  if (r != M4D_OK || info.fps_den == 0) {
    return Status(M4D_ERR_BITSTREAM, "GOP index: damaged SEQUENCE_HEADER");
  }
  *fps = static_cast<double>(info.fps_num) / info.fps_den;
  return Status::Ok();
}

bool KeyframePacket(uint32_t type) {
  return type == M4D_PACKET_SEQUENCE_HEADER || type == M4D_PACKET_KEYFRAME_STATIC ||
         type == M4D_PACKET_KEYFRAME_DYNAMIC || type == M4D_PACKET_STATIC_UPDATE;
}

}  // namespace

Status BuildGopIndex(const uint8_t* data, size_t size, GopIndex* index) {
  *index = GopIndex();
  index->stream_bytes = size;
  size_t pos = 0, frame_start = 0;
  bool frame_open = false, keyframe = false, sequence_header = false;
  int64_t frame_index = 0;
  while (pos < size) {
    M4dPacketInfo info;
    const int r = m4d_parse_packet_header(data + pos, size - pos, &info);
    if (r != M4D_OK) {
      return Status(M4D_ERR_BITSTREAM,
                    "GOP index: damaged or truncated packet at byte " + std::to_string(pos));
    }
    if (!frame_open) {
      frame_open = true;
      frame_start = pos;
      frame_index = info.frame_index;
      keyframe = sequence_header = false;
    }
    if (info.type == M4D_PACKET_SEQUENCE_HEADER) {
      sequence_header = true;
      if (index->fps == 0)
        M4D_RETURN_IF_ERROR(StreamFps(data + pos, info.packet_size, &index->fps));
    }
    keyframe = keyframe || KeyframePacket(info.type);
    pos += info.packet_size;
    if (!info.end_of_frame) continue;
    frame_open = false;
    if (keyframe) {
      GopEntry gop;
      gop.frame = frame_index;
      gop.offset = frame_start;
      gop.random_access = sequence_header;
      index->gops.push_back(gop);
    } else if (index->gops.empty()) {
      return Status(M4D_ERR_BITSTREAM, "GOP index: an inter frame before any keyframe");
    }
    ++index->gops.back().frames;
    ++index->frames;
  }
  if (frame_open) return Status(M4D_ERR_BITSTREAM, "GOP index: the stream ends inside a frame");
  for (size_t g = 0; g < index->gops.size(); ++g) {
    const uint64_t end = g + 1 < index->gops.size() ? index->gops[g + 1].offset : size;
    index->gops[g].bytes = end - index->gops[g].offset;
  }
  return Status::Ok();
}

std::string GopIndexJson(const GopIndex& index) {
  nlohmann::json gops = nlohmann::json::array();
  for (const GopEntry& g : index.gops) {
    gops.push_back({{"frame", g.frame},
                    {"frames", g.frames},
                    {"offset", g.offset},
                    {"bytes", g.bytes},
                    {"random_access", g.random_access}});
  }
  const nlohmann::json json = {
      {"format", "m4d-gop-index"}, {"version", 1},     {"stream_bytes", index.stream_bytes},
      {"frames", index.frames},    {"fps", index.fps}, {"gops", gops}};
  return json.dump(2) + "\n";
}

}  // namespace m4d
