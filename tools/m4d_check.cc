// m4d_check: validates a stream against the specification, for checking any encoder's output.
// Stricter than a decoder, which skips what it may (packets before the first
// SEQUENCE_HEADER, data after damage): every packet must parse, follow the stream grammar of
// spec 2 (packet order, end_of_frame, frame numbering) and decode without error with payload
// CRCs checked; every payload's CRC is checked even where the decoder skips the rest of a GOP
// after an error, and damaged headers are skipped as a decoder does, so that every damaged
// packet is listed. Prints every violation with its byte offset, then a summary (GOPs, frames,
// bytes per packet type, a note when num_frames, which is informative, disagrees); exits 0
// only for a conforming stream.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "m4d/m4d.h"
#include "sdk/src/common/crc32.h"
#include "tools/usage_exit.h"

namespace {

constexpr uint32_t kLastType = M4D_PACKET_APPEARANCE;
const char* kTypeNames[] = {"?",           "SEQUENCE_HEADER", "KEYFRAME_STATIC", "KEYFRAME_DYNAMIC",
                            "MLP_WEIGHTS", "MOTION_GRID",     "COMPENSATION",    "STATIC_UPDATE",
                            "APPEARANCE"};

const char* TypeName(uint32_t type) { return type <= kLastType ? kTypeNames[type] : "unknown"; }

// The grammar of spec 2 as the packet types that may follow each one.
bool MayFollow(uint32_t previous, uint32_t type) {
  switch (previous) {
    case 0:  // stream start
      return type == M4D_PACKET_SEQUENCE_HEADER;
    case M4D_PACKET_SEQUENCE_HEADER:
      return type == M4D_PACKET_KEYFRAME_STATIC || type == M4D_PACKET_KEYFRAME_DYNAMIC;
    case M4D_PACKET_KEYFRAME_STATIC:
    case M4D_PACKET_STATIC_UPDATE:
      return type == M4D_PACKET_KEYFRAME_DYNAMIC;
    case M4D_PACKET_KEYFRAME_DYNAMIC:
      return type == M4D_PACKET_MLP_WEIGHTS;
    case M4D_PACKET_MOTION_GRID:
      return type == M4D_PACKET_APPEARANCE || type == M4D_PACKET_COMPENSATION;
    case M4D_PACKET_APPEARANCE:
      return type == M4D_PACKET_COMPENSATION;
    default:  // MLP_WEIGHTS or COMPENSATION ended a frame; a dependent keyframe may follow
      return type == M4D_PACKET_SEQUENCE_HEADER || type == M4D_PACKET_MOTION_GRID ||
             type == M4D_PACKET_STATIC_UPDATE || type == M4D_PACKET_KEYFRAME_DYNAMIC;
  }
}

struct Checker {
  int violations = 0;
  uint32_t previous = 0;        // type of the previous packet, 0 at the start
  uint32_t frame = 0;           // frame_index of the previous packet
  bool resynchronised = false;  // damaged bytes were skipped just before this packet
  int gops = 0, frames = 0;
  uint32_t declared_frames = 0;
  size_t bytes[kLastType + 1] = {};

  void Violation(size_t offset, const std::string& what) {
    ++violations;
    std::printf("byte %zu: %s\n", offset, what.c_str());
  }

  void CheckGrammar(size_t offset, const M4dPacketInfo& info) {
    if (!resynchronised) CheckOrder(offset, info);
    resynchronised = false;
    const uint32_t type = info.type;
    const char* name = TypeName(type);
    const bool ends = type == M4D_PACKET_MLP_WEIGHTS || type == M4D_PACKET_COMPENSATION;
    if ((info.end_of_frame != 0) != ends) {
      Violation(offset, std::string(name) + (ends ? " without" : " with") + " end_of_frame");
    }
    const bool ended = previous == M4D_PACKET_MLP_WEIGHTS || previous == M4D_PACKET_COMPENSATION;
    gops += type == M4D_PACKET_SEQUENCE_HEADER ||
            (ended && (type == M4D_PACKET_STATIC_UPDATE || type == M4D_PACKET_KEYFRAME_DYNAMIC));
    frames += ends;
    previous = type <= kLastType ? type : previous;
    frame = info.frame_index;
  }

  // Packet order and frame numbering against the previous packet. Not after
  // skipped bytes: what they held is unknown, and the damage is reported already.
  void CheckOrder(size_t offset, const M4dPacketInfo& info) {
    const uint32_t type = info.type;
    const char* name = TypeName(type);
    if (!MayFollow(previous, type)) {
      Violation(offset, std::string(name) + " may not follow " + kTypeNames[previous]);
    }
    const bool ended = previous == M4D_PACKET_MLP_WEIGHTS || previous == M4D_PACKET_COMPENSATION;
    const bool starts_frame = type == M4D_PACKET_SEQUENCE_HEADER || ended;
    if (starts_frame && type != M4D_PACKET_SEQUENCE_HEADER && info.frame_index != frame + 1) {
      Violation(offset, "frame " + std::to_string(info.frame_index) + " after frame " +
                            std::to_string(frame) + " in a GOP");
    }
    if (!starts_frame && previous != 0 && info.frame_index != frame) {
      Violation(offset, std::string(name) + " of frame " + std::to_string(info.frame_index) +
                            " inside frame " + std::to_string(frame));
    }
  }
};

// num_frames of a SEQUENCE_HEADER (payload offset 12, u32 little-endian).
uint32_t DeclaredFrames(const uint8_t* packet) {
  const uint8_t* p = packet + 24 + 12;
  return p[0] | p[1] << 8 | p[2] << 16 | static_cast<uint32_t>(p[3]) << 24;
}

// Checked here, not only by the decoder: after a rejected packet the decoder skips the rest of
// its GOP, and a second damaged packet there would go unreported.
bool PayloadCrcMatches(const uint8_t* packet, const M4dPacketInfo& info) {
  const uint8_t* c = packet + 16;  // payload_crc, u32 little-endian
  const uint32_t crc = c[0] | c[1] << 8 | c[2] << 16 | static_cast<uint32_t>(c[3]) << 24;
  return m4d::Crc32(packet + 24, info.payload_size) == crc;
}

// The offset of the next packet header after damaged bytes at `from` (the end when none).
size_t Resync(const std::vector<uint8_t>& data, size_t from) {
  size_t offset = 0;
  M4dPacketInfo info;
  const int r = m4d_find_packet(data.data() + from, data.size() - from, &offset, &info);
  return (r == M4D_OK || info.packet_size > 0) ? from + offset : data.size();
}

}  // namespace

int main(int argc, char** argv) {
  std::string input;
  CLI::App app{"Check that a stream conforms to the M4D specification (for encoder output)."};
  app.add_option("stream", input, "stream file")->required()->check(CLI::ExistingFile);
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  std::ifstream file(input, std::ios::binary);
  const std::vector<uint8_t> data((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) < 0) return 1;
  Checker check;
  size_t pos = 0;
  while (pos < data.size()) {
    M4dPacketInfo info;
    int r = m4d_parse_packet_header(&data[pos], data.size() - pos, &info);
    if (r == M4D_ERR_AGAIN) {
      check.Violation(pos, "the stream ends inside a packet");
      break;
    }
    if (r < 0) {
      // Resynchronise as a decoder does (spec 3), to report the damage after this too.
      check.Violation(pos, std::string("packet header: ") + m4d_error_string(r));
      m4d_flush(ctx);
      pos = Resync(data, pos + 1);
      check.resynchronised = true;
      continue;
    }
    check.CheckGrammar(pos, info);
    const bool crc_ok = PayloadCrcMatches(&data[pos], info);
    if (!crc_ok) {
      check.Violation(pos, std::string(TypeName(info.type)) + " (frame " +
                               std::to_string(info.frame_index) + "): payload CRC mismatch");
    }
    if (info.type == M4D_PACKET_SEQUENCE_HEADER && info.payload_size >= 16) {
      const uint32_t declared = DeclaredFrames(&data[pos]);
      if (check.declared_frames == 0) check.declared_frames = declared;
    }
    if (info.type <= kLastType) check.bytes[info.type] += info.packet_size;
    r = m4d_send_packet(ctx, &data[pos], info.packet_size);
    M4dFrame frame;
    while (r == M4D_ERR_AGAIN && m4d_get_frame(ctx, &frame) == M4D_OK) {
      m4d_frame_unref(&frame);
      r = m4d_send_packet(ctx, &data[pos], info.packet_size);
    }
    while (m4d_get_frame(ctx, &frame) == M4D_OK) m4d_frame_unref(&frame);
    // A payload CRC mismatch is reported above.
    if (r < 0 && (crc_ok || r != M4D_ERR_CHECKSUM)) {
      check.Violation(pos, std::string("decoding: ") + m4d_last_error(ctx));
    }
    pos += info.packet_size;
  }
  m4d_close(&ctx);
  if (check.previous != 0 && check.previous != M4D_PACKET_MLP_WEIGHTS &&
      check.previous != M4D_PACKET_COMPENSATION) {
    check.Violation(data.size(), "the stream ends inside a frame");
  }
  if (data.empty()) check.Violation(0, "empty stream");
  if (check.declared_frames != 0 && check.declared_frames != static_cast<uint32_t>(check.frames)) {
    // Informative in the specification: a note, not a violation.
    std::printf("note: num_frames declares %u frames, the stream has %d\n", check.declared_frames,
                check.frames);
  }
  std::printf("%s: %d GOPs, %d frames, %zu bytes\n", input.c_str(), check.gops, check.frames,
              data.size());
  for (uint32_t t = 1; t <= kLastType; ++t) {
    std::printf("  %-18s %12zu bytes\n", kTypeNames[t], check.bytes[t]);
  }
  std::printf("%s\n", check.violations == 0
                          ? "conforms"
                          : (std::to_string(check.violations) + " violations").c_str());
  return check.violations == 0 ? 0 : 1;
}
