// m4d_probe: what a stream holds, as ffprobe shows it for video: the stream's configuration
// (bitstream version, frame rate, SH degree, declared frames), then per GOP and per frame the
// packets with their types and sizes, the decoded Gaussians per layer and the frame hash, and
// every error with its byte offset. A table, or JSON with --json. Reads the stream as a player
// does (bitstream-spec 3: resynchronise after damage); exits 1 when anything was damaged or
// the stream holds no frame. With --gop-index it prints (or writes with -o) the stream's GOP
// index instead, the JSON sidecar (STREAM.m4d.gops.json) that an HTTP player fetches by.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/io/atomic_file.h"
#include "encoder/src/stream/gop_index.h"
#include "m4d/m4d.h"
#include "tools/existing_output.h"
#include "tools/usage_exit.h"

namespace {

const char* kTypeNames[] = {"?",           "SEQUENCE_HEADER", "KEYFRAME_STATIC", "KEYFRAME_DYNAMIC",
                            "MLP_WEIGHTS", "MOTION_GRID",     "COMPENSATION",    "STATIC_UPDATE",
                            "APPEARANCE"};

const char* TypeName(uint32_t type) {
  return type <= M4D_PACKET_APPEARANCE ? kTypeNames[type] : "unknown";
}

struct PacketRow {
  size_t offset = 0;
  uint32_t type = 0;
  size_t size = 0;
  bool damaged = false;  // rejected by the decoder
};

struct FrameRow {
  uint32_t index = 0;
  bool keyframe = false;
  bool random_access = false;  // its packets include a SEQUENCE_HEADER
  std::vector<PacketRow> packets;
  uint32_t static_count = 0, dynamic_count = 0;
  uint32_t concealed = 0;  // M4dFrame.concealed_layers: layers lost to damage (spec 6.8)
  std::string hash;
  size_t bytes() const {
    size_t total = 0;
    for (const PacketRow& p : packets) total += p.size;
    return total;
  }
};

// ErrorRow.code when the stream ends inside a packet or a frame: TRUNCATED (spec 9), as
// m4d_decode names it, not an M4D_ERR_* code; -100 as in the WebAssembly API.
constexpr int kTruncated = -100;

struct ErrorRow {
  size_t offset = 0;
  int code = 0;  // M4D_ERR_* or kTruncated
  std::string message;
};

// The names of bitstream-spec 9, as m4d_decode's first_error line gives them.
const char* ErrorName(int code) {
  switch (code) {
    case kTruncated:
      return "TRUNCATED";
    case M4D_ERR_NOMEM:
      return "M4D_ERR_NOMEM";
    case M4D_ERR_BITSTREAM:
      return "M4D_ERR_BITSTREAM";
    case M4D_ERR_CHECKSUM:
      return "M4D_ERR_CHECKSUM";
    case M4D_ERR_UNSUPPORTED:
      return "M4D_ERR_UNSUPPORTED";
    case M4D_ERR_LIMIT:
      return "M4D_ERR_LIMIT";
    default:
      return "UNKNOWN";
  }
}

const char* ErrorText(int code) {
  return code == kTruncated ? "truncated" : m4d_error_string(code);
}

struct Probe {
  std::vector<FrameRow> frames;
  std::vector<ErrorRow> errors;
  std::vector<PacketRow> pending;  // packets of the frame being decoded
  M4dStreamInfo info{};
  bool configured = false;
};

std::string Hex(const uint8_t md5[16]) {
  char text[33];
  for (int i = 0; i < 16; ++i) std::snprintf(text + 2 * i, 3, "%02x", md5[i]);
  return text;
}

void TakeFrames(M4dContext* ctx, Probe* probe) {
  M4dFrame frame;
  while (m4d_get_frame(ctx, &frame) == M4D_OK) {
    FrameRow row;
    row.index = frame.frame_index;
    row.keyframe = frame.is_keyframe != 0;
    row.packets.swap(probe->pending);
    for (const PacketRow& p : row.packets) {
      row.random_access = row.random_access || p.type == M4D_PACKET_SEQUENCE_HEADER;
    }
    row.static_count = frame.static_layer.count;
    row.dynamic_count = frame.dynamic_layer.count;
    row.concealed = frame.concealed_layers;
    uint8_t md5[16];
    if (m4d_frame_hash(&frame, md5) == M4D_OK) row.hash = Hex(md5);
    probe->frames.push_back(std::move(row));
    m4d_frame_unref(&frame);
  }
}

// The offset of the next packet header at or after `from`, or the end.
size_t Resync(const std::vector<uint8_t>& data, size_t from) {
  size_t offset = 0;
  M4dPacketInfo info;
  const int r = m4d_find_packet(data.data() + from, data.size() - from, &offset, &info);
  return (r == M4D_OK || info.packet_size > 0) ? from + offset : data.size();
}

void Run(const std::vector<uint8_t>& data, Probe* probe) {
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) != M4D_OK) {
    probe->errors.push_back({0, M4D_ERR_NOMEM, "cannot open a decoder"});
    return;
  }
  size_t pos = 0;
  bool inside_frame = false;  // the last packet header read has no end_of_frame (spec 3, 5)
  while (pos < data.size()) {
    M4dPacketInfo info;
    int r = m4d_parse_packet_header(&data[pos], data.size() - pos, &info);
    if (r == M4D_ERR_AGAIN) {
      probe->errors.push_back({pos, kTruncated, "the stream ends inside a packet"});
      inside_frame = false;  // one truncation, as m4d_decode reports it
      break;
    }
    if (r < 0) {
      probe->errors.push_back({pos, r, "damaged packet header; resynchronising"});
      m4d_flush(ctx);
      probe->pending.clear();
      pos = Resync(data, pos + 1);
      continue;
    }
    inside_frame = !info.end_of_frame;
    probe->pending.push_back({pos, info.type, info.packet_size});
    r = m4d_send_packet(ctx, &data[pos], info.packet_size);
    if (r == M4D_ERR_AGAIN) {
      TakeFrames(ctx, probe);
      r = m4d_send_packet(ctx, &data[pos], info.packet_size);
    }
    // A damaged payload may still end a frame, output with that layer concealed (spec 6.8).
    if (r < 0) probe->pending.back().damaged = true;
    TakeFrames(ctx, probe);
    // A frame that ended without output (skipped after damage): its packets are not the next's.
    if (info.end_of_frame) probe->pending.clear();
    if (r < 0) {
      probe->errors.push_back({pos, r, m4d_last_error(ctx)});
      pos = Resync(data, pos + 24);
      continue;
    }
    pos += info.packet_size;
  }
  if (inside_frame) {
    probe->errors.push_back(
        {data.size(), kTruncated, "the stream ends inside a frame (its last packet is missing)"});
  }
  probe->configured = m4d_get_stream_info(ctx, &probe->info) == M4D_OK;
  m4d_close(&ctx);
}

const char* ConcealedNote(uint32_t concealed) {
  if (concealed == M4D_LAYER_ALL) return "; both layers concealed";
  if (concealed == M4D_LAYER_STATIC) return "; static layer concealed";
  return concealed == M4D_LAYER_DYNAMIC ? "; dynamic layer concealed" : "";
}

// GOPs as (first frame row, end row): a GOP starts at each keyframe.
std::vector<std::pair<size_t, size_t>> Gops(const Probe& probe) {
  std::vector<std::pair<size_t, size_t>> gops;
  for (size_t i = 0; i < probe.frames.size(); ++i) {
    if (probe.frames[i].keyframe || gops.empty()) gops.emplace_back(i, i);
    gops.back().second = i + 1;
  }
  return gops;
}

void PrintTable(const std::string& path, size_t size, const Probe& probe) {
  const M4dStreamInfo& s = probe.info;
  std::printf("%s: %zu bytes", path.c_str(), size);
  if (probe.configured) {
    std::printf(", bitstream %u.%u, %u/%u fps, SH degree %u, %u frames declared", s.bitstream_major,
                s.bitstream_minor, s.fps_num, s.fps_den, s.sh_degree, s.num_frames);
  }
  std::printf("\n");
  for (const auto& [first, end] : Gops(probe)) {
    size_t bytes = 0;
    for (size_t i = first; i < end; ++i) bytes += probe.frames[i].bytes();
    const FrameRow& key = probe.frames[first];
    std::printf("\nGOP at frame %u (%s), %zu frames, %.2f KB\n", key.index,
                key.random_access ? "random access" : (key.keyframe ? "dependent" : "no keyframe"),
                end - first, bytes / 1000.0);
    std::printf("%6s %5s %9s %9s %10s  %-32s %s\n", "frame", "type", "static", "dynamic", "bytes",
                "hash", "packets (bytes)");
    for (size_t i = first; i < end; ++i) {
      const FrameRow& f = probe.frames[i];
      std::string packets;
      for (const PacketRow& p : f.packets) {
        packets += (packets.empty() ? "" : ", ") + std::string(TypeName(p.type)) + " " +
                   std::to_string(p.size) + (p.damaged ? " damaged" : "");
      }
      std::printf("%6u %5s %9u %9u %10zu  %-32s %s%s\n", f.index,
                  f.keyframe ? (f.random_access ? "key" : "dkey") : "inter", f.static_count,
                  f.dynamic_count, f.bytes(), f.hash.c_str(), packets.c_str(),
                  ConcealedNote(f.concealed));
    }
  }
  std::printf("\n%zu frames, %zu errors\n", probe.frames.size(), probe.errors.size());
  for (const ErrorRow& e : probe.errors) {
    if (e.code == kTruncated) {  // worded as m4d_decode words it
      std::printf("  byte %zu: truncated: %s\n", e.offset, e.message.c_str());
    } else {
      std::printf("  byte %zu: error %d (%s): %s\n", e.offset, e.code, m4d_error_string(e.code),
                  e.message.c_str());
    }
  }
}

nlohmann::json ToJson(const std::string& path, size_t size, const Probe& probe) {
  using nlohmann::json;
  json stream = {{"file", path}, {"bytes", size}};
  if (probe.configured) {
    const M4dStreamInfo& s = probe.info;
    stream["bitstream_version"] =
        std::to_string(s.bitstream_major) + "." + std::to_string(s.bitstream_minor);
    stream["fps_num"] = s.fps_num;
    stream["fps_den"] = s.fps_den;
    stream["sh_degree"] = s.sh_degree;
    stream["num_frames_declared"] = s.num_frames;
  }
  json frames = json::array();
  for (const FrameRow& f : probe.frames) {
    json packets = json::array();
    for (const PacketRow& p : f.packets) {
      packets.push_back({{"offset", p.offset},
                         {"type", TypeName(p.type)},
                         {"bytes", p.size},
                         {"damaged", p.damaged}});
    }
    json concealed = json::array();
    if (f.concealed & M4D_LAYER_STATIC) concealed.push_back("static");
    if (f.concealed & M4D_LAYER_DYNAMIC) concealed.push_back("dynamic");
    frames.push_back({{"frame", f.index},
                      {"keyframe", f.keyframe},
                      {"random_access", f.random_access},
                      {"static_gaussians", f.static_count},
                      {"dynamic_gaussians", f.dynamic_count},
                      {"bytes", f.bytes()},
                      {"hash", f.hash},
                      {"concealed_layers", concealed},
                      {"packets", packets}});
  }
  json gops = json::array();
  for (const auto& [first, end] : Gops(probe)) {
    size_t bytes = 0;
    for (size_t i = first; i < end; ++i) bytes += probe.frames[i].bytes();
    gops.push_back({{"first_frame", probe.frames[first].index},
                    {"frames", end - first},
                    {"random_access", probe.frames[first].random_access},
                    {"bytes", bytes}});
  }
  json errors = json::array();
  for (const ErrorRow& e : probe.errors) {
    errors.push_back({{"offset", e.offset},
                      {"code", e.code},
                      {"name", ErrorName(e.code)},
                      {"error", ErrorText(e.code)},
                      {"message", e.message}});
  }
  return {{"stream", stream}, {"gops", gops}, {"frames", frames}, {"errors", errors}};
}

// --gop-index: the index on stdout, or written atomically to `output`; 1 for a damaged stream.
int WriteGopIndex(const std::string& input, const std::vector<uint8_t>& data,
                  const std::string& output) {
  m4d::GopIndex index;
  const m4d::Status built = m4d::BuildGopIndex(data.data(), data.size(), &index);
  if (!built.ok()) {
    std::fprintf(stderr, "m4d_probe: %s: %s\n", input.c_str(), built.message().c_str());
    return 1;
  }
  const std::string json = m4d::GopIndexJson(index);
  if (output.empty()) {
    std::fputs(json.c_str(), stdout);
    return 0;
  }
  const m4d::Status written =
      m4d::WriteFileAtomically(output, reinterpret_cast<const uint8_t*>(json.data()), json.size());
  if (!written.ok()) {
    std::fprintf(stderr, "m4d_probe: %s\n", written.message().c_str());
    return 1;
  }
  std::printf("%s: %zu GOPs, %lld frames\n", output.c_str(), index.gops.size(),
              static_cast<long long>(index.frames));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string input;
  std::string output;
  bool json = false, gop_index = false, force = false;
  CLI::App app{"Show what an M4D stream holds: configuration, GOPs, frames, packets, errors."};
  app.add_option("stream", input, "stream file")->required()->check(CLI::ExistingFile);
  CLI::Option* gops = app.add_flag("--gop-index", gop_index,
                                   "the GOP index (JSON) an HTTP player fetches by, instead");
  app.add_flag("--json", json, "JSON instead of the table")->excludes(gops);
  app.add_option("-o,--output", output, "--gop-index: write it to this file (else stdout)")
      ->needs(gops);
  app.add_flag("-f,--force", force, "replace an existing output (else refused)")->needs(gops);
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  if (!output.empty()) {
    const m4d::Status may_write = m4d::RefuseExistingOutput(output, force);
    if (!may_write.ok()) {
      std::fprintf(stderr, "m4d_probe: %s\n", may_write.message().c_str());
      return 2;
    }
  }
  std::ifstream file(input, std::ios::binary);
  const std::vector<uint8_t> data((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
  if (!file.good() && !file.eof()) {
    std::fprintf(stderr, "m4d_probe: cannot read %s: %s\n", input.c_str(), std::strerror(errno));
    return 1;
  }
  if (gop_index) return WriteGopIndex(input, data, output);
  Probe probe;
  Run(data, &probe);
  if (json) {
    std::printf("%s\n", ToJson(input, data.size(), probe).dump(2).c_str());
  } else {
    PrintTable(input, data.size(), probe);
  }
  return probe.errors.empty() && !probe.frames.empty() ? 0 : 1;
}
