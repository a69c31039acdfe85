// The C API of the SDK (sdk/include/m4d/m4d.h) over the C++ Decoder. Nothing may throw
// through this boundary: allocation failures become M4D_ERR_NOMEM.
#include <climits>
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "m4d/m4d.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/decode/decoder.h"
#include "sdk/src/decode/frame_hash.h"

struct M4dContext {
  M4dSettings settings;
  std::unique_ptr<m4d::Decoder> decoder;
  std::string last_error;
  M4dDataProps frame_props;  // of the packet that completed the pending frame
};

namespace {

// What M4dFrame.internal points to: keeps the frame's sets alive.
struct FrameRefs {
  std::shared_ptr<const m4d::GaussianSet> static_layer;
  std::shared_ptr<const m4d::GaussianSet> dynamic_layer;
};

void Log(const M4dContext* c, int level, const std::string& message) {
  if (c->settings.logger.callback) {
    c->settings.logger.callback(c->settings.logger.cookie, level, message.c_str());
  }
}

int Fail(M4dContext* c, int code, const std::string& message) {
  c->last_error = message;
  Log(c, M4D_LOG_ERROR, message);
  return code;
}

// Reserved bytes must be zero, so that a later field can give them a meaning.
template <size_t N>
bool ReservedZero(const uint8_t (&reserved)[N]) {
  for (uint8_t b : reserved) {
    if (b != 0) return false;
  }
  return true;
}

constexpr int kMaxThreads = 256;

}  // namespace

extern "C" {

#define M4D_STRINGIFY_(x) #x
#define M4D_STRINGIFY(x) M4D_STRINGIFY_(x)
const char* m4d_version(void) {
  return M4D_STRINGIFY(M4D_VERSION_MAJOR) "." M4D_STRINGIFY(M4D_VERSION_MINOR) "." M4D_STRINGIFY(
      M4D_VERSION_PATCH);
}

const char* m4d_error_string(int code) {
  switch (code) {
    case M4D_OK:
      return "success";
    case M4D_ERR_AGAIN:
      return "try again (output pending or no frame ready)";
    case M4D_ERR_INVALID_ARG:
      return "invalid argument";
    case M4D_ERR_NOMEM:
      return "out of memory";
    case M4D_ERR_BITSTREAM:
      return "invalid bitstream";
    case M4D_ERR_CHECKSUM:
      return "checksum mismatch";
    case M4D_ERR_UNSUPPORTED:
      return "unsupported bitstream feature or version";
    case M4D_ERR_LIMIT:
      return "a declared size exceeds a limit";
    default:
      return "unknown error";
  }
}

void m4d_default_settings(M4dSettings* s) {
  if (!s) return;
  std::memset(s, 0, sizeof(*s));
  s->layers = M4D_LAYER_ALL;
  s->verify_checksums = 1;
  s->threads = 1;
}

void m4d_default_data_props(M4dDataProps* props) {
  if (!props) return;
  std::memset(props, 0, sizeof(*props));
  props->timestamp = INT64_MIN;
  props->offset = -1;
}

int m4d_open(M4dContext** c_out, const M4dSettings* s) {
  if (!c_out) return M4D_ERR_INVALID_ARG;
  *c_out = nullptr;
  if (!s || s->layers == 0 || (s->layers & ~M4D_LAYER_ALL) != 0 || !ReservedZero(s->reserved) ||
      (s->allocator.alloc == nullptr) != (s->allocator.free == nullptr) ||
      (s->verify_checksums != 0 && s->verify_checksums != 1) || s->threads < 0 ||
      s->threads > kMaxThreads) {
    return M4D_ERR_INVALID_ARG;
  }
  M4dContext* c = new (std::nothrow) M4dContext();
  if (!c) return M4D_ERR_NOMEM;
  c->settings = *s;
  m4d::DecoderOptions options;
  options.layers = s->layers;
  options.max_gaussians = s->max_gaussians;
  options.max_grid_values = s->max_grid_values;
  options.verify_checksums = s->verify_checksums != 0;
  options.threads = s->threads;
  options.allocator = &c->settings.allocator;
  options.log = [c](int level, const std::string& message) { Log(c, level, message); };
  try {
    c->decoder = std::make_unique<m4d::Decoder>(options);
  } catch (const std::bad_alloc&) {
    delete c;
    return M4D_ERR_NOMEM;
  }
  m4d_default_data_props(&c->frame_props);
  *c_out = c;
  return M4D_OK;
}

int m4d_parse_packet_header(const uint8_t* data, size_t size, M4dPacketInfo* info) {
  if (!data || !info) return M4D_ERR_INVALID_ARG;
  std::memset(info, 0, sizeof(*info));
  m4d::PacketHeader h;
  const m4d::Status status = m4d::ParsePacketHeader(data, size, &h);
  if (!status.ok()) return status.code();
  info->type = h.type;
  info->frame_index = h.frame_index;
  info->end_of_frame = h.end_of_frame() ? 1 : 0;
  info->payload_size = h.payload_size;
  info->packet_size = m4d::kPacketHeaderSize + h.payload_size;
  return size < info->packet_size ? M4D_ERR_AGAIN : M4D_OK;
}

int m4d_find_packet(const uint8_t* data, size_t size, size_t* offset, M4dPacketInfo* info) {
  if (!data || !offset || !info) return M4D_ERR_INVALID_ARG;
  for (size_t p = 0; p + m4d::kPacketHeaderSize <= size; ++p) {
    if (data[p] != m4d::kPacketSync[0]) continue;
    const int r = m4d_parse_packet_header(data + p, size - p, info);
    if (r == M4D_OK || r == M4D_ERR_AGAIN) {
      *offset = p;
      return r;
    }
  }
  // A header may still start in the last 23 bytes.
  *offset = size < m4d::kPacketHeaderSize ? 0 : size - (m4d::kPacketHeaderSize - 1);
  *info = M4dPacketInfo();
  return M4D_ERR_AGAIN;
}

int m4d_find_random_access(const uint8_t* data, size_t size, uint32_t frame_index, size_t* offset,
                           uint32_t* start_frame) {
  if (!data || !offset || !start_frame) return M4D_ERR_INVALID_ARG;
  bool have_start = false;  // a SEQUENCE_HEADER seen so far: the last one's offset and frame
  size_t start = 0;
  uint32_t first = 0;
  size_t pos = 0;
  while (pos < size) {
    size_t skip = 0;
    M4dPacketInfo info;
    if (m4d_find_packet(data + pos, size - pos, &skip, &info) != M4D_OK) break;
    pos += skip;
    if (info.type == M4D_PACKET_SEQUENCE_HEADER) {
      have_start = true;
      start = pos;
      first = info.frame_index;
    }
    // The first packet of the frame: its GOP's SEQUENCE_HEADER, if any, came before it.
    if (info.frame_index == frame_index) {
      if (!have_start) return M4D_ERR_BITSTREAM;
      *offset = start;
      *start_frame = first;
      return M4D_OK;
    }
    pos += info.packet_size;
  }
  return M4D_ERR_AGAIN;
}

int m4d_send_packet(M4dContext* c, const uint8_t* data, size_t size) {
  return m4d_send_packet_props(c, data, size, nullptr);
}

int m4d_send_packet_props(M4dContext* c, const uint8_t* data, size_t size,
                          const M4dDataProps* props) {
  if (!c) return M4D_ERR_INVALID_ARG;
  if (!data) return Fail(c, M4D_ERR_INVALID_ARG, "m4d_send_packet: data is NULL");
  if (props && !ReservedZero(props->reserved)) {
    return Fail(c, M4D_ERR_INVALID_ARG, "m4d_send_packet_props: non-zero reserved bytes");
  }
  if (c->decoder->HasFrame()) return M4D_ERR_AGAIN;
  c->last_error.clear();
  try {
    const m4d::Status status = c->decoder->SendPacket(data, size);
    // A rejected packet may still complete a frame (a damaged payload, spec 6.8).
    if (c->decoder->HasFrame()) {
      if (props) {
        c->frame_props = *props;
      } else {
        m4d_default_data_props(&c->frame_props);
      }
    }
    if (!status.ok()) return Fail(c, status.code(), status.message());
  } catch (const std::bad_alloc&) {
    c->decoder->Flush();
    return Fail(c, M4D_ERR_NOMEM, "out of memory while decoding a packet");
  }
  return M4D_OK;
}

int m4d_get_frame(M4dContext* c, M4dFrame* out) {
  if (!c || !out) return M4D_ERR_INVALID_ARG;
  std::memset(out, 0, sizeof(*out));
  if (!c->decoder->HasFrame()) return M4D_ERR_AGAIN;
  FrameRefs* refs = new (std::nothrow) FrameRefs();
  if (!refs) return Fail(c, M4D_ERR_NOMEM, "out of memory for a frame");
  m4d::DecodedFrame frame = c->decoder->TakeFrame();
  refs->static_layer = std::move(frame.static_layer);
  refs->dynamic_layer = std::move(frame.dynamic_layer);
  out->frame_index = frame.frame_index;
  out->is_keyframe = frame.is_keyframe ? 1 : 0;
  out->layers = frame.layers;
  out->concealed_layers = frame.concealed;
  out->static_layer = m4d::GaussianView(*refs->static_layer);
  out->dynamic_layer = m4d::GaussianView(*refs->dynamic_layer);
  out->props = c->frame_props;
  out->internal = refs;
  return M4D_OK;
}

int m4d_get_stream_info(const M4dContext* c, M4dStreamInfo* info) {
  if (!c || !info) return M4D_ERR_INVALID_ARG;
  std::memset(info, 0, sizeof(*info));
  const m4d::StreamStats& s = c->decoder->stream_stats();
  if (!s.configured) return M4D_ERR_AGAIN;
  info->bitstream_major = static_cast<uint32_t>(s.sequence.version_major);
  info->bitstream_minor = static_cast<uint32_t>(s.sequence.version_minor);
  info->profile = static_cast<uint32_t>(s.sequence.profile);
  info->sh_degree = static_cast<uint32_t>(s.sequence.sh_degree);
  info->fps_num = s.sequence.fps_num;
  info->fps_den = s.sequence.fps_den;
  info->num_frames = s.sequence.num_frames;
  info->layers_coded = M4D_LAYER_DYNAMIC | (s.static_coded ? M4D_LAYER_STATIC : 0u);
  info->frames_decoded = s.frames;
  info->gops = s.gops;
  info->random_access_gops = s.random_access_gops;
  info->last_keyframe_index = s.last_keyframe;
  info->last_random_access_index = s.last_random_access;
  info->up_axis = static_cast<uint32_t>(s.sequence.up_axis);
  return M4D_OK;
}

void m4d_flush(M4dContext* c) {
  if (c) c->decoder->Flush();
}

int m4d_set_background(M4dContext* c, const M4dGaussians* bg) {
  if (!c) return M4D_ERR_INVALID_ARG;
  if (!bg) {
    c->decoder->SetBackground(nullptr);
    return M4D_OK;
  }
  const uint32_t max =
      c->settings.max_gaussians ? c->settings.max_gaussians : m4d::kMaxGaussiansPerSet;
  if (bg->sh_degree > 3 || bg->count > max ||
      bg->sh_coefficients != static_cast<uint32_t>(m4d::ShCoefficients(bg->sh_degree)) ||
      (bg->count > 0 &&
       (!bg->positions || !bg->log_scales || !bg->rotations || !bg->opacity_logits || !bg->sh))) {
    return Fail(c, M4D_ERR_INVALID_ARG, "m4d_set_background: inconsistent Gaussian arrays");
  }
  try {
    auto set = std::make_shared<m4d::GaussianSet>(&c->settings.allocator);
    set->sh_degree = static_cast<int>(bg->sh_degree);
    const size_t n = bg->count;
    if (n > 0) {
      set->positions.assign(bg->positions, bg->positions + 3 * n);
      set->log_scales.assign(bg->log_scales, bg->log_scales + 3 * n);
      set->rotations.assign(bg->rotations, bg->rotations + 4 * n);
      set->opacity_logits.assign(bg->opacity_logits, bg->opacity_logits + n);
      set->sh.assign(bg->sh, bg->sh + static_cast<size_t>(set->sh_floats()) * n);
    }
    c->decoder->SetBackground(std::move(set));
  } catch (const std::bad_alloc&) {
    return Fail(c, M4D_ERR_NOMEM, "m4d_set_background: out of memory");
  }
  return M4D_OK;
}

const char* m4d_last_error(const M4dContext* c) { return c ? c->last_error.c_str() : ""; }

void m4d_frame_unref(M4dFrame* frame) {
  if (!frame) return;
  delete static_cast<FrameRefs*>(frame->internal);
  std::memset(frame, 0, sizeof(*frame));
}

int m4d_frame_hash(const M4dFrame* frame, uint8_t md5[16]) {
  if (!frame || !md5) return M4D_ERR_INVALID_ARG;
  m4d::FrameHash(frame->static_layer, frame->dynamic_layer, frame->concealed_layers, md5);
  return M4D_OK;
}

void m4d_close(M4dContext** c) {
  if (!c || !*c) return;
  delete *c;
  *c = nullptr;
}

}  // extern "C"
