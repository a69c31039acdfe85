// BuildGopIndex: the packets split as m4d_probe splits them (m4d_parse_packet_header), frames
// grouped by end_of_frame, a GOP started at each frame holding a KEYFRAME_DYNAMIC (spec 2), and
// every packet sent to a decoder so that a damaged payload is an error, not a wrong index.
#include "encoder/src/stream/gop_index.h"

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "m4d/m4d.h"

namespace m4d {
namespace {

struct ContextCloser {
  void operator()(M4dContext* ctx) const { m4d_close(&ctx); }
};

Status At(size_t offset, int code, const std::string& message) {
  return Status(code, "byte " + std::to_string(offset) + ": " + message);
}

// Takes the frames the decoder has ready; returns how many.
int64_t DrainFrames(M4dContext* ctx) {
  int64_t count = 0;
  M4dFrame frame;
  while (m4d_get_frame(ctx, &frame) == M4D_OK) {
    m4d_frame_unref(&frame);
    ++count;
  }
  return count;
}

Status Build(const uint8_t* data, size_t size, GopIndex* index) {
  if (size == 0) return BitstreamError("the stream is empty");
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* raw = nullptr;
  if (m4d_open(&raw, &settings) != M4D_OK) return Status(M4D_ERR_NOMEM, "cannot open a decoder");
  const std::unique_ptr<M4dContext, ContextCloser> ctx(raw);

  size_t pos = 0, frame_start = 0;
  bool inside_frame = false, frame_random_access = false, frame_keyframe = false;
  uint32_t frame_index = 0;
  int64_t decoded = 0;
  while (pos < size) {
    M4dPacketInfo info;
    int r = m4d_parse_packet_header(data + pos, size - pos, &info);
    if (r == M4D_ERR_AGAIN) {
      return At(pos, M4D_ERR_BITSTREAM, "the stream ends inside a packet (truncated)");
    }
    if (r < 0) return At(pos, r, "damaged packet header");
    if (!inside_frame) {
      frame_start = pos;
      frame_index = info.frame_index;
      frame_random_access = frame_keyframe = false;
      inside_frame = true;
    }
    frame_random_access = frame_random_access || info.type == M4D_PACKET_SEQUENCE_HEADER;
    frame_keyframe = frame_keyframe || info.type == M4D_PACKET_KEYFRAME_DYNAMIC;
    r = m4d_send_packet(ctx.get(), data + pos, info.packet_size);
    if (r == M4D_ERR_AGAIN) {
      decoded += DrainFrames(ctx.get());
      r = m4d_send_packet(ctx.get(), data + pos, info.packet_size);
    }
    if (r < 0) return At(pos, r, m4d_last_error(ctx.get()));
    decoded += DrainFrames(ctx.get());
    pos += info.packet_size;
    if (!info.end_of_frame) continue;
    inside_frame = false;
    if (frame_keyframe) {
      GopEntry gop;
      gop.frame = frame_index;
      gop.offset = frame_start;
      gop.random_access = frame_random_access;
      index->gops.push_back(gop);
    } else if (index->gops.empty()) {
      return At(frame_start, M4D_ERR_BITSTREAM,
                "frame " + std::to_string(frame_index) + " comes before any keyframe");
    }
    ++index->gops.back().frames;
    ++index->frames;
  }
  if (inside_frame) {
    return At(size, M4D_ERR_BITSTREAM,
              "the stream ends inside a frame (its last packet is missing; truncated)");
  }
  if (index->gops.empty()) return BitstreamError("the stream holds no frame");
  if (!index->gops.front().random_access) {
    return At(0, M4D_ERR_BITSTREAM, "the stream does not start with a random-access keyframe");
  }
  if (decoded != index->frames) {
    return BitstreamError(std::to_string(index->frames) + " frames in the stream but " +
                          std::to_string(decoded) + " decoded");
  }
  for (size_t i = 0; i < index->gops.size(); ++i) {
    const uint64_t end = i + 1 < index->gops.size() ? index->gops[i + 1].offset : size;
    index->gops[i].bytes = end - index->gops[i].offset;
  }
  M4dStreamInfo info;
  if (m4d_get_stream_info(ctx.get(), &info) == M4D_OK && info.fps_den != 0) {
    index->fps = static_cast<double>(info.fps_num) / info.fps_den;
  }
  index->stream_bytes = size;
  return Status::Ok();
}

}  // namespace

Status BuildGopIndex(const uint8_t* data, size_t size, GopIndex* index) {
  if (index == nullptr || (data == nullptr && size > 0)) {
    return Status(M4D_ERR_INVALID_ARG, "BuildGopIndex: null argument");
  }
  *index = GopIndex();
  const Status status = Build(data, size, index);
  if (!status.ok()) *index = GopIndex();
  return status;
}

nlohmann::ordered_json GopsJson(const std::vector<GopEntry>& gops) {
  nlohmann::ordered_json json = nlohmann::ordered_json::array();
  for (const GopEntry& g : gops) {
    json.push_back({{"frame", g.frame},
                    {"frames", g.frames},
                    {"offset", g.offset},
                    {"bytes", g.bytes},
                    {"random_access", g.random_access}});
  }
  return json;
}

std::string GopIndexJson(const GopIndex& index) {
  const nlohmann::ordered_json gops = GopsJson(index.gops);
  const nlohmann::ordered_json json = {
      {"format", "m4d-gop-index"}, {"version", 1},     {"stream_bytes", index.stream_bytes},
      {"frames", index.frames},    {"fps", index.fps}, {"gops", gops}};
  return json.dump(2) + "\n";
}

}  // namespace m4d
