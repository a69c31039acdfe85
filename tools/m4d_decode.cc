// m4d_decode: decodes an M4D stream with the public C API and prints one line per frame,
// "<frame_index> <md5>", the normative frame hash (bitstream-spec section 7). This is the
// command-line contract the conformance runner uses to check a decoder.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "m4d/m4d.h"
#include "tools/existing_output.h"
#include "tools/number_checks.h"
#include "tools/usage_exit.h"

namespace {

struct Options {
  std::string input;
  std::string output;
  std::string layers = "all";
  int start_gop = 0;
  int64_t start_frame = -1;
  int threads = 1;
  bool quiet = false;
  bool force = false;  // replace an existing --output
};

void LogToStderr(void*, int level, const char* message) {
  // Errors are reported with their byte offsets by the read loop.
  if (level == M4D_LOG_WARNING) std::fprintf(stderr, "m4d: %s\n", message);
}

void Hex(const uint8_t md5[16], char out[33]) {
  for (int i = 0; i < 16; ++i) std::snprintf(out + 2 * i, 3, "%02x", md5[i]);
}

// The offset of the next packet header at or after `from` (the end when none); counts the
// bytes passed over.
size_t Resync(const std::vector<uint8_t>& data, size_t from, size_t* skipped) {
  size_t offset = 0;
  M4dPacketInfo info;
  const int r = m4d_find_packet(data.data() + from, data.size() - from, &offset, &info);
  const size_t next = (r == M4D_OK || info.packet_size > 0) ? from + offset : data.size();
  *skipped += next - from;
  return next;
}

// The names of bitstream-spec 9, for the conformance contract's first_error line.
const char* ErrorName(int code) {
  switch (code) {
    case M4D_ERR_INVALID_ARG:
      return "M4D_ERR_INVALID_ARG";
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

// ".partial.NAME" beside `path`.
std::string PartialPath(const std::string& path) {
  const size_t slash = path.rfind('/');
  const size_t name = slash == std::string::npos ? 0 : slash + 1;
  return path.substr(0, name) + ".partial." + path.substr(name);
}

const char* ConcealedLayers(uint32_t layers) {
  if (layers == M4D_LAYER_ALL) return "both layers";
  return layers == M4D_LAYER_STATIC ? "static layer" : "dynamic layer";
}

// Reports an error with its byte offset; the first one also as the conformance contract's
// line "first_error NAME" (conformance/README.md).
class ErrorReport {
 public:
  void Error(size_t offset, int code, const char* detail) {
    std::fprintf(stderr, "m4d_decode: byte %zu: error %d (%s): %s\n", offset, code,
                 m4d_error_string(code), detail);
    First(ErrorName(code));
  }
  // The stream ends inside a packet or a frame (spec 9, TRUNCATED).
  void Truncated(size_t offset, const char* where) {
    std::fprintf(stderr, "m4d_decode: byte %zu: truncated: the stream ends inside a %s\n", offset,
                 where);
    First("TRUNCATED");
  }
  int count() const { return count_; }

 private:
  void First(const char* name) {
    if (count_++ == 0) std::fprintf(stderr, "first_error %s\n", name);
  }
  int count_ = 0;
};

// Which frames a seek outputs: those from the target on, in stream order. Frame numbers wrap
// at 2^32, so they are compared by their distance from the random-access point's frame, where
// decoding starts (no other SEQUENCE_HEADER comes before the target, so the numbers count up).
struct SeekTarget {
  uint32_t start = 0;   // the first frame of the random-access GOP decoding starts at
  uint32_t target = 0;  // the frame sought
  bool reached = true;  // once reached, every later frame is output
  bool Reached(uint32_t frame_index) {
    reached = reached || frame_index - start >= target - start;
    return reached;
  }
};

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  CLI::App app{"Decode an M4D stream and print the hash of every frame."};
  app.add_option("stream", opt.input, "stream file")->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", opt.output, "write the hash lines to this file, not stdout");
  app.add_option("--layers", opt.layers, "layers to output")
      ->check(CLI::IsMember({"all", "static", "dynamic"}));
  app.add_option("--start-gop", opt.start_gop,
                 "seek: start decoding at this random-access GOP (0-based; dependent GOPs "
                 "are not counted: decoding cannot start there)")
      ->check(m4d::AtLeast(0));
  app.add_option("--start-frame", opt.start_frame,
                 "seek: decode from the random-access point at or before this frame index and "
                 "print the frames from it on in stream order (m4d_find_random_access)")
      ->check(m4d::Within(int64_t{0}, int64_t{UINT32_MAX}))
      ->excludes("--start-gop");
  app.add_option("--threads", opt.threads, "decoder threads (0: every core); output is the same")
      ->check(m4d::Within(0, 256));
  app.add_flag("-q,--quiet", opt.quiet, "no summary on stderr");
  app.add_flag("-f,--force", opt.force, "replace an existing --output (else refused)");
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  const m4d::Status may_write = m4d::RefuseExistingOutput(opt.output, opt.force);
  if (!opt.output.empty() && !may_write.ok()) {
    std::fprintf(stderr, "m4d_decode: %s\n", may_write.message().c_str());
    return 2;
  }

  std::ifstream file(opt.input, std::ios::binary);
  std::vector<uint8_t> data((std::istreambuf_iterator<char>(file)),
                            std::istreambuf_iterator<char>());
  if (!file.good() && !file.eof()) {
    std::fprintf(stderr, "m4d_decode: cannot read %s: %s\n", opt.input.c_str(),
                 std::strerror(errno));
    return 1;
  }

  M4dSettings settings;
  m4d_default_settings(&settings);
  settings.layers = opt.layers == "static"    ? M4D_LAYER_STATIC
                    : opt.layers == "dynamic" ? M4D_LAYER_DYNAMIC
                                              : M4D_LAYER_ALL;
  settings.logger.callback = LogToStderr;
  settings.threads = opt.threads;
  M4dContext* ctx = nullptr;
  if (m4d_open(&ctx, &settings) < 0) return 1;

  ErrorReport errors;
  int frames = 0, gop = -1, concealed = 0;
  bool inside_frame = false;  // the last packet header read has no end_of_frame
  size_t pos = 0, skipped = 0;
  SeekTarget seek;
  if (opt.start_frame >= 0) {
    uint32_t first = 0;
    const uint32_t target = static_cast<uint32_t>(opt.start_frame);
    const int r = m4d_find_random_access(data.data(), data.size(), target, &pos, &first);
    seek = {first, target, false};
    if (r < 0) {
      std::fprintf(stderr, "m4d_decode: cannot seek to frame %u: %s\n", target,
                   r == M4D_ERR_AGAIN ? "the stream holds no such frame"
                                      : "no random-access point precedes it");
      m4d_close(&ctx);
      return 1;
    }
  }
  FILE* out = stdout;
  // The hash lines go to a partial file renamed at the end: an interrupted run leaves no
  // file that looks complete.
  const std::string partial = PartialPath(opt.output);
  if (!opt.output.empty() && !(out = std::fopen(partial.c_str(), "w"))) {
    std::fprintf(stderr, "m4d_decode: cannot write %s: %s\n", opt.output.c_str(),
                 std::strerror(errno));
    m4d_close(&ctx);
    return 1;
  }
  double decode_ms = 0;
  M4dPacketInfo info;
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) {
      if (!seek.Reached(frame.frame_index)) {
        m4d_frame_unref(&frame);  // decoded only to reach the frame sought
        continue;
      }
      uint8_t md5[16];
      char hex[33];
      m4d_frame_hash(&frame, md5);
      Hex(md5, hex);
      std::fprintf(out, "%u %s\n", frame.frame_index, hex);
      ++frames;
      if (frame.concealed_layers != 0) {
        ++concealed;
        std::fprintf(stderr, "m4d_decode: frame %u: %s concealed (damaged stream)\n",
                     frame.frame_index, ConcealedLayers(frame.concealed_layers));
      }
      m4d_frame_unref(&frame);
    }
  };
  // Read as bitstream-spec 3 says: after a damaged header flush (the skipped bytes may have
  // held a packet the decoder cannot miss by itself, an optional KEYFRAME_STATIC) and resume
  // at the next header; after a failed packet resume right after its header (a dropped byte
  // leaves its payload_size pointing past the next one).
  while (pos < data.size()) {
    int r = m4d_parse_packet_header(&data[pos], data.size() - pos, &info);
    if (r == M4D_ERR_AGAIN) {
      errors.Truncated(pos, "packet");
      inside_frame = false;
      break;
    }
    if (r < 0) {
      errors.Error(pos, r, "damaged packet header; resynchronising");
      m4d_flush(ctx);
      pos = Resync(data, pos + 1, &skipped);
      continue;
    }
    inside_frame = !info.end_of_frame;
    if (info.type == M4D_PACKET_SEQUENCE_HEADER) ++gop;
    // From the start every packet goes to the decoder, also those before the first
    // SEQUENCE_HEADER: it checks their type before skipping them (bitstream-spec 9, E7, E13).
    if (opt.start_gop == 0 || gop >= opt.start_gop || opt.start_frame >= 0) {
      const auto t0 = std::chrono::steady_clock::now();
      r = m4d_send_packet(ctx, &data[pos], info.packet_size);
      if (r == M4D_ERR_AGAIN) {
        drain();
        r = m4d_send_packet(ctx, &data[pos], info.packet_size);
      }
      decode_ms +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      drain();
      if (r < 0) {
        errors.Error(pos, r, m4d_last_error(ctx));
        pos = Resync(data, pos + 24, &skipped);
        continue;
      }
    }
    pos += info.packet_size;
  }
  if (inside_frame) errors.Truncated(data.size(), "frame (its last packet is missing)");
  M4dStreamInfo stream;
  const bool configured = m4d_get_stream_info(ctx, &stream) == M4D_OK;
  m4d_close(&ctx);
  if (out != stdout &&
      (std::fclose(out) != 0 || std::rename(partial.c_str(), opt.output.c_str()))) {
    std::fprintf(stderr, "m4d_decode: cannot write %s: %s\n", opt.output.c_str(),
                 std::strerror(errno));
    std::remove(partial.c_str());
    return 1;
  }
  if (opt.start_gop > 0 && gop < opt.start_gop) {
    std::fprintf(stderr,
                 "m4d_decode: cannot start at GOP %d: the stream has %d random-access GOPs\n",
                 opt.start_gop, gop + 1);
    return 1;
  }
  if (frames == 0) std::fprintf(stderr, "m4d_decode: no frame decoded\n");
  if (!opt.quiet) {
    std::fprintf(stderr,
                 "m4d_decode: %d frames (%d concealed), %d packet errors, %zu bytes skipped, "
                 "%.1f ms\n",
                 frames, concealed, errors.count(), skipped, decode_ms);
    if (configured) {
      std::fprintf(stderr,
                   "m4d_decode: bitstream %u.%u, %u/%u fps, SH degree %u, %u GOPs (%u random "
                   "access), %u frames declared\n",
                   stream.bitstream_major, stream.bitstream_minor, stream.fps_num, stream.fps_den,
                   stream.sh_degree, stream.gops, stream.random_access_gops, stream.num_frames);
    }
  }
  return (errors.count() > 0 || skipped > 0 || frames == 0) ? 1 : 0;
}
