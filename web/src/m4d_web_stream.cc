// The WebAssembly module's entry points: a stream reader that takes a stream's bytes in any
// chunks (as fetch delivers them), splits them into packets, decodes them with the public C
// API and hands out one frame at a time, reading damaged streams as bitstream-spec 3 says
// (the loop of tools/m4d_decode.cc, made incremental). JavaScript (web/js/m4d.mjs) calls
// these through the module's exports; every function is C ABI.
#include <emscripten/emscripten.h>

#include <cstddef>
#include <cstdint>
#include <new>

#include "web/src/m4d_web_stream.h"

namespace {

constexpr size_t kHeaderSize = 24;  // bitstream-spec 3

// What the reader reports of the last damage it met. code is an M4D_ERR_* code, or
// kTruncated when the stream ends inside a packet.
constexpr int kTruncated = -100;

}  // namespace

namespace {

void RecordError(M4dWebStream* s, size_t offset, int code, const std::string& message) {
  if (s->error_count++ == 0) s->first_error_code = code;
  s->last_error_offset = offset;
  s->last_error_code = code;
  s->last_error_message = message;
}

// Moves position to the next packet header (m4d_find_packet). Returns false when the bytes
// received so far hold none and more may come.
bool Resynchronise(M4dWebStream* s) {
  size_t offset = 0;
  M4dPacketInfo info;
  const size_t available = s->bytes.size() - s->position;
  const int r = m4d_find_packet(s->bytes.data() + s->position, available, &offset, &info);
  if (r == M4D_OK || info.packet_size > 0) {
    s->skipped_bytes += offset;
    s->position += offset;
    s->resynchronising = false;
    return true;
  }
  // No header starts in the first `offset` bytes; the rest may begin one.
  s->skipped_bytes += offset;
  s->position += offset;
  if (!s->ended) return false;
  s->skipped_bytes += s->bytes.size() - s->position;
  s->position = s->bytes.size();
  s->resynchronising = false;
  return true;
}

// Whether a seek has reached its target: from it on, every frame is output in stream order.
bool SeekReached(M4dWebStream* s, uint32_t frame_index) {
  s->seeking = s->seeking && frame_index - s->seek_start < s->seek_target - s->seek_start;
  return !s->seeking;
}

// Takes a decoded frame into s->frame, dropping those before a seek's target.
bool TakeFrame(M4dWebStream* s) {
  while (m4d_get_frame(s->context, &s->frame) == M4D_OK) {
    if (SeekReached(s, s->frame.frame_index)) {
      s->holding_frame = true;
      return true;
    }
    m4d_frame_unref(&s->frame);
  }
  return false;
}

// Sends the packet at position. Returns true when a frame is ready.
bool SendPacket(M4dWebStream* s, const M4dPacketInfo& info) {
  const uint8_t* packet = s->bytes.data() + s->position;
  int r = m4d_send_packet(s->context, packet, info.packet_size);
  if (r == M4D_ERR_AGAIN) return TakeFrame(s);  // the same packet is sent again next time
  if (r < 0) {
    RecordError(s, s->position, r, m4d_last_error(s->context));
    s->position += kHeaderSize;  // a damaged payload's size may be wrong
    s->resynchronising = true;
  } else {
    s->position += info.packet_size;
  }
  return TakeFrame(s);
}

}  // namespace

extern "C" {

// Opens a reader whose decoder outputs `layers` (M4D_LAYER_* bits) and accepts at most
// `max_gaussians` Gaussians in a layer (0: the spec's limit; M4dSettings.max_gaussians).
// Returns NULL when out of memory or for bad layers.
EMSCRIPTEN_KEEPALIVE M4dWebStream* m4dw_stream_open(uint32_t layers, uint32_t max_gaussians) {
  M4dWebStream* s = new (std::nothrow) M4dWebStream;
  if (s == nullptr) return nullptr;
  M4dSettings settings;
  m4d_default_settings(&settings);
  settings.layers = layers;
  settings.max_gaussians = max_gaussians;
  if (m4d_open(&s->context, &settings) < 0) {
    delete s;
    return nullptr;
  }
  return s;
}

// Closes the reader, its decoder and the frame it holds.
EMSCRIPTEN_KEEPALIVE void m4dw_stream_close(M4dWebStream* s) {
  if (s == nullptr) return;
  m4d_frame_unref(&s->frame);
  m4d_close(&s->context);
  delete s;
}

// Makes room for `size` more bytes of the stream and returns where the caller writes them
// (NULL when out of memory). The bytes count as received once written.
EMSCRIPTEN_KEEPALIVE uint8_t* m4dw_stream_reserve(M4dWebStream* s, size_t size) {
  if (s == nullptr || s->ended) return nullptr;
  try {
    s->bytes.resize(s->bytes.size() + size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
  return s->bytes.data() + s->bytes.size() - size;
}

// Declares that no more bytes come: a packet cut at the end is then an error.
EMSCRIPTEN_KEEPALIVE void m4dw_stream_end(M4dWebStream* s) {
  if (s != nullptr) s->ended = true;
}

// Releases the frame handed out last and decodes up to the next one. Returns 1 when a frame
// is ready (m4dw_frame_*), 0 when more bytes are needed or, after m4dw_stream_end, the
// stream is over. Damage does not stop it: it is counted (m4dw_stream_error_count) and
// reading resumes as bitstream-spec 3 says.
EMSCRIPTEN_KEEPALIVE int m4dw_stream_next_frame(M4dWebStream* s) {
  if (s == nullptr) return 0;
  if (s->holding_frame) {
    m4d_frame_unref(&s->frame);
    s->holding_frame = false;
  }
  if (TakeFrame(s)) return 1;
  while (s->position < s->bytes.size()) {
    if (s->resynchronising) {
      if (!Resynchronise(s)) return 0;
      continue;
    }
    M4dPacketInfo info;
    const int r = m4d_parse_packet_header(s->bytes.data() + s->position,
                                          s->bytes.size() - s->position, &info);
    if (r == M4D_ERR_AGAIN) {
      if (!s->ended) return 0;
      RecordError(s, s->position, kTruncated, "the stream ends inside a packet");
      s->position = s->bytes.size();
      s->inside_frame = false;
      return 0;
    }
    if (r < 0) {
      RecordError(s, s->position, r, "damaged packet header; resynchronising");
      m4d_flush(s->context);
      s->position += 1;
      s->resynchronising = true;
      continue;
    }
    s->inside_frame = info.end_of_frame == 0;
    if (SendPacket(s, info)) return 1;
  }
  if (s->ended && s->inside_frame) {
    RecordError(s, s->position, kTruncated, "the stream ends inside a frame");
    s->inside_frame = false;
  }
  return 0;
}

// Restarts decoding at the random-access point at or before frame `frame_index` among the
// bytes received so far (m4d_find_random_access); frames before it are then dropped. Returns
// 0, M4D_ERR_AGAIN when the frame is not among those bytes, or M4D_ERR_BITSTREAM when no
// random-access GOP precedes it. Then the frames from it on come in stream order.
EMSCRIPTEN_KEEPALIVE int m4dw_stream_seek(M4dWebStream* s, uint32_t frame_index) {
  if (s == nullptr) return M4D_ERR_INVALID_ARG;
  size_t offset = 0;
  uint32_t start_frame = 0;
  const int r =
      m4d_find_random_access(s->bytes.data(), s->bytes.size(), frame_index, &offset, &start_frame);
  if (r < 0) return r;
  m4d_frame_unref(&s->frame);
  s->holding_frame = false;
  m4d_flush(s->context);
  s->position = offset;
  s->resynchronising = false;
  s->seeking = true;
  s->seek_start = start_frame;
  s->seek_target = frame_index;
  return M4D_OK;
}

// Replaces the static layer of s's frames by the static layer of the frame `source` holds (a
// background from another stream), from the next frame on; source NULL restores the stream's
// own (m4d_set_background).
EMSCRIPTEN_KEEPALIVE int m4dw_stream_set_background(M4dWebStream* s, const M4dWebStream* source) {
  if (s == nullptr) return M4D_ERR_INVALID_ARG;
  if (source == nullptr) return m4d_set_background(s->context, nullptr);
  if (!source->holding_frame) return M4D_ERR_INVALID_ARG;
  return m4d_set_background(s->context, &source->frame.static_layer);
}

// The reader's decoder, for the public C API (m4d_get_stream_info).
EMSCRIPTEN_KEEPALIVE M4dContext* m4dw_stream_context(M4dWebStream* s) {
  return s != nullptr ? s->context : nullptr;
}

EMSCRIPTEN_KEEPALIVE int m4dw_stream_error_count(const M4dWebStream* s) { return s->error_count; }
EMSCRIPTEN_KEEPALIVE double m4dw_stream_last_error_offset(const M4dWebStream* s) {
  return static_cast<double>(s->last_error_offset);
}
// M4D_ERR_* codes, or -100 when the stream ended inside a packet; 0 before any error.
EMSCRIPTEN_KEEPALIVE int m4dw_stream_first_error_code(const M4dWebStream* s) {
  return s->first_error_code;
}
EMSCRIPTEN_KEEPALIVE int m4dw_stream_last_error_code(const M4dWebStream* s) {
  return s->last_error_code;
}
EMSCRIPTEN_KEEPALIVE const char* m4dw_stream_last_error_message(const M4dWebStream* s) {
  return s->last_error_message.c_str();
}
EMSCRIPTEN_KEEPALIVE double m4dw_stream_skipped_bytes(const M4dWebStream* s) {
  return static_cast<double>(s->skipped_bytes);
}
EMSCRIPTEN_KEEPALIVE double m4dw_stream_buffered_bytes(const M4dWebStream* s) {
  return static_cast<double>(s->bytes.size());
}

// The frame handed out by m4dw_stream_next_frame (valid until the next call on the reader).
EMSCRIPTEN_KEEPALIVE uint32_t m4dw_frame_index(const M4dWebStream* s) {
  return s->frame.frame_index;
}
EMSCRIPTEN_KEEPALIVE int m4dw_frame_is_keyframe(const M4dWebStream* s) {
  return s->frame.is_keyframe;
}
EMSCRIPTEN_KEEPALIVE uint32_t m4dw_frame_layers(const M4dWebStream* s) { return s->frame.layers; }
// The layers lost to damage and concealed (M4dFrame.concealed_layers).
EMSCRIPTEN_KEEPALIVE uint32_t m4dw_frame_concealed_layers(const M4dWebStream* s) {
  return s->frame.concealed_layers;
}
// The frame's M4dGaussians of `layer` (M4D_LAYER_STATIC or M4D_LAYER_DYNAMIC). In wasm32 it
// is eight 32-bit words: count, sh_degree, sh_coefficients, then the five array addresses.
EMSCRIPTEN_KEEPALIVE const M4dGaussians* m4dw_frame_layer(const M4dWebStream* s, uint32_t layer) {
  return layer == M4D_LAYER_STATIC ? &s->frame.static_layer : &s->frame.dynamic_layer;
}
// The frame itself, for m4d_frame_hash.
EMSCRIPTEN_KEEPALIVE const M4dFrame* m4dw_frame(const M4dWebStream* s) { return &s->frame; }

}  // extern "C"

static_assert(sizeof(void*) == 4 && offsetof(M4dGaussians, positions) == 12 &&
                  offsetof(M4dGaussians, sh) == 28,
              "web/js/m4d.mjs reads M4dGaussians as eight 32-bit words");
