/*
 * m4d.h - public C API of the M4D decoder SDK.
 *
 * M4D streams carry volumetric video made of 3D Gaussians, coded with the motion-decoupled
 * scheme of 4D-MoDe (static background layer, dynamic foreground layer moved by a motion grid
 * and a shared MLP). The format is specified in bitstream-spec/README.md.
 *
 * Typical use:
 *
 *     M4dSettings s;
 *     m4d_default_settings(&s);
 *     M4dContext *c;
 *     if (m4d_open(&c, &s) < 0) ...
 *     for each packet (split a file with m4d_parse_packet_header):
 *         int r = m4d_send_packet(c, data, size);
 *         while r == M4D_ERR_AGAIN: drain frames with m4d_get_frame, then send again
 *         M4dFrame f;
 *         while (m4d_get_frame(c, &f) == 0) { use f; m4d_frame_unref(&f); }
 *     m4d_close(&c);
 *
 * Every function returns 0 (M4D_OK) or a negative M4D_ERR_* code. A context is used by one
 * thread at a time; separate contexts are independent (the library has no global state).
 * Frames stay valid after the context is closed, until m4d_frame_unref.
 */
#ifndef M4D_M4D_H_
#define M4D_M4D_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define M4D_API __attribute__((visibility("default")))
#else
#define M4D_API
#endif

/* ABI version of this API (the shared library's soname is libm4d.so.MAJOR). MAJOR rises with
 * any change that breaks a program built against an earlier header (a struct's layout, a
 * removed function, changed semantics), MINOR with additions (a function, a setting taken from
 * a reserved field), PATCH with fixes. A program built against MAJOR.MINOR runs with any library
 * of the same MAJOR and a MINOR at least as high. */
#define M4D_API_VERSION_MAJOR 1
#define M4D_API_VERSION_MINOR 1
#define M4D_API_VERSION_PATCH 0

/* Library version (of this SDK), and the bitstream version it decodes. */
#define M4D_VERSION_MAJOR 0
#define M4D_VERSION_MINOR 9
#define M4D_VERSION_PATCH 0
#define M4D_BITSTREAM_VERSION_MAJOR 0
#define M4D_BITSTREAM_VERSION_MINOR 11 /* decodes 0.2 to 0.10 streams too */

/* Error codes. Every failing call returns one of these (always negative). */
#define M4D_OK 0
#define M4D_ERR_AGAIN (-1)       /* try again: output pending, or no frame ready yet */
#define M4D_ERR_INVALID_ARG (-2) /* API misuse: NULL pointer, bad setting, wrong order */
#define M4D_ERR_NOMEM (-3)       /* an allocation failed */
#define M4D_ERR_BITSTREAM (-4)   /* the stream violates the specification */
#define M4D_ERR_CHECKSUM (-5)    /* a packet header or payload CRC does not match */
#define M4D_ERR_UNSUPPORTED (-6) /* valid syntax this decoder does not implement */
#define M4D_ERR_LIMIT (-7)       /* a declared count or size exceeds a limit */

/* Layers, as bits of M4dSettings.layers and M4dFrame.layers. */
#define M4D_LAYER_STATIC 1u  /* keyframe static background */
#define M4D_LAYER_DYNAMIC 2u /* dynamic foreground: keyframe set moved by motion */
#define M4D_LAYER_ALL (M4D_LAYER_STATIC | M4D_LAYER_DYNAMIC)

/* Packet types (bitstream-spec section 2). */
typedef enum M4dPacketType {
  M4D_PACKET_SEQUENCE_HEADER = 1,
  M4D_PACKET_KEYFRAME_STATIC = 2,
  M4D_PACKET_KEYFRAME_DYNAMIC = 3,
  M4D_PACKET_MLP_WEIGHTS = 4,
  M4D_PACKET_MOTION_GRID = 5,
  M4D_PACKET_COMPENSATION = 6,
  M4D_PACKET_STATIC_UPDATE = 7, /* bitstream 0.3: the static set's change at a dependent keyframe */
  M4D_PACKET_APPEARANCE = 8 /* bitstream 0.3: the dynamic set's colour change at an inter frame */
} M4dPacketType;

/* Log levels passed to M4dLogger.callback. */
/* M4dStreamInfo.up_axis: the world axis that points up (spec 4.1). Many captures keep
 * OpenCV's camera convention, y down: M4D_UP_NEG_Y. */
typedef enum M4dUpAxis {
  M4D_UP_UNKNOWN = 0,
  M4D_UP_POS_X = 1,
  M4D_UP_NEG_X = 2,
  M4D_UP_POS_Y = 3,
  M4D_UP_NEG_Y = 4,
  M4D_UP_POS_Z = 5,
  M4D_UP_NEG_Z = 6
} M4dUpAxis;

typedef enum M4dLogLevel { M4D_LOG_ERROR = 0, M4D_LOG_WARNING = 1, M4D_LOG_INFO = 2 } M4dLogLevel;

/* Logger hook. callback may be NULL (the default): nothing is logged. Messages are one line,
 * without a trailing newline, and valid only during the call. */
typedef struct M4dLogger {
  void* cookie;
  void (*callback)(void* cookie, int level, const char* message);
} M4dLogger;

/* Allocator hook for the decoder's large buffers (Gaussian arrays, motion grids, payload
 * copies). Both callbacks NULL (the default) means malloc/free. alloc returns NULL on failure;
 * the call that needed the memory then returns M4D_ERR_NOMEM and the context stays usable.
 * Small bookkeeping and the Draco library's internal allocations use the C++ heap. */
typedef struct M4dAllocator {
  void* cookie;
  void* (*alloc)(void* cookie, size_t size);
  void (*free)(void* cookie, void* ptr);
} M4dAllocator;

/* Decoder settings. Always initialise with m4d_default_settings(). */
typedef struct M4dSettings {
  /* Layers to output: M4D_LAYER_STATIC, M4D_LAYER_DYNAMIC or both. Packets of the other layer
   * are checked (header CRC) and skipped, never decoded. Default: M4D_LAYER_ALL. */
  uint32_t layers;
  /* Largest Gaussian count accepted in any one layer; larger declarations fail with
   * M4D_ERR_LIMIT before any allocation. 0 means the specification's limit (2^22).
   * Default: 0. */
  uint32_t max_gaussians;
  /* Largest motion grid accepted, in values summed over levels; 0 means the
   * specification's limit (2^24). Default: 0. */
  uint32_t max_grid_values;
  /* Verify payload CRCs. 1 (default) or 0 (skip; only for trusted, pre-verified input). */
  int verify_checksums;
  M4dLogger logger;       /* default: no logging */
  M4dAllocator allocator; /* default: malloc/free */
  /* Threads decoding may use, the caller's included: 1 decodes on the calling thread only,
   * 0 uses every core, at most 256. Only work whose result cannot depend on it is split
   * (motion of the dynamic Gaussians, one Gaussian per task): output is bit-identical at
   * every count. Default: 1. */
  int threads;
  uint8_t reserved[32]; /* for future settings; must stay zero */
} M4dSettings;

/* What a caller attaches to a packet (m4d_send_packet_props) and gets back with the frame
 * the packet completes, dav1d's Dav1dDataProps: the decoder never reads it. */
typedef struct M4dDataProps {
  int64_t timestamp; /* the caller's presentation time; INT64_MIN (default): none */
  int64_t duration;  /* the caller's duration; 0 (default): none */
  int64_t offset;    /* e.g. the packet's byte offset in a file; -1 (default): none */
  void* user_data;   /* anything; NULL by default */
  uint8_t reserved[16];
} M4dDataProps;

/* One layer's Gaussians. Values are as coded (before activation): log scales, opacity logits,
 * unnormalised rotation quaternions (w, x, y, z), SH coefficients. Arrays hold count entries of
 * the stated width, Gaussian after Gaussian; they are NULL when count is 0. */
typedef struct M4dGaussians {
  uint32_t count;
  uint32_t sh_degree;          /* 0..3 */
  uint32_t sh_coefficients;    /* (sh_degree + 1)^2 per colour channel */
  const float* positions;      /* 3 per Gaussian: x, y, z */
  const float* log_scales;     /* 3 per Gaussian */
  const float* rotations;      /* 4 per Gaussian: w, x, y, z */
  const float* opacity_logits; /* 1 per Gaussian */
  const float* sh;             /* 3 * sh_coefficients per Gaussian: [k][r, g, b] */
  uint8_t reserved[16];        /* zero; room for later fields */
} M4dGaussians;

/* A decoded frame: the Gaussian state of frame frame_index. */
typedef struct M4dFrame {
  uint32_t frame_index;
  int is_keyframe;            /* 1 at the start of a GOP: a random access point unless the
                                 GOP is dependent (bitstream 0.3, spec 2) */
  uint32_t layers;            /* the layers this frame outputs (M4D_LAYER_* bits) */
  M4dGaussians static_layer;  /* background; count 0 if not output */
  M4dGaussians dynamic_layer; /* foreground; count 0 if not output */
  /* The props sent with the packet that completed this frame (its last packet: MLP_WEIGHTS or
   * COMPENSATION); the defaults of M4dDataProps when that packet came without. */
  M4dDataProps props;
  void* internal; /* owned by the library; release with m4d_frame_unref */
  /* Layers (M4D_LAYER_* bits) lost to a damaged payload (bitstream-spec 6.8): their content is
   * a concealment, not the stream's. The static layer is then the last one output (the
   * previous GOP's, or empty), the dynamic layer frozen at its last frame output. 0 for an
   * intact frame. The frame hash counts a concealed layer as not output. */
  uint32_t concealed_layers;
  uint8_t reserved[28]; /* zero; room for later fields */
} M4dFrame;

/* What m4d_parse_packet_header reads from a packet header. */
typedef struct M4dPacketInfo {
  uint32_t type; /* M4dPacketType */
  uint32_t frame_index;
  int end_of_frame;
  uint32_t payload_size;
  size_t packet_size; /* header plus payload */
  uint8_t reserved[16];
} M4dPacketInfo;

/* What the decoder knows of the stream (m4d_get_stream_info): the configuration of the last
 * SEQUENCE_HEADER it decoded and what it has seen since it was opened. */
typedef struct M4dStreamInfo {
  uint32_t bitstream_major, bitstream_minor; /* of the stream, e.g. 0.3 */
  uint32_t profile;
  uint32_t sh_degree; /* 0..3 */
  uint32_t fps_num;   /* frame rate fps_num / fps_den, as the stream declares it */
  uint32_t fps_den;
  uint32_t num_frames; /* frames the stream declares; 0: not declared (e.g. live) */
  /* M4D_LAYER_STATIC when the current random-access GOP codes a static layer
   * (KEYFRAME_STATIC), M4D_LAYER_DYNAMIC always. */
  uint32_t layers_coded;
  uint32_t frames_decoded;           /* frames output so far (m4d_get_frame) */
  uint32_t gops;                     /* keyframes decoded so far, dependent ones included */
  uint32_t random_access_gops;       /* of which started with a SEQUENCE_HEADER */
  uint32_t last_keyframe_index;      /* frame index of the last keyframe decoded */
  uint32_t last_random_access_index; /* frame index of the last random-access keyframe */
  /* The world direction that is up in the stream's content (M4dUpAxis), as its encoder
   * states it; M4D_UP_UNKNOWN before bitstream 0.9 or when not stated. API 1.1. */
  uint32_t up_axis;
  uint8_t reserved[60];
} M4dStreamInfo;

/* Opaque decoder context. */
typedef struct M4dContext M4dContext;

/* Returns the library version as "major.minor.patch". Never NULL. */
M4D_API const char* m4d_version(void);

/* Returns a static English description of an M4D_ERR_* code. Never NULL. */
M4D_API const char* m4d_error_string(int code);

/* Fills *s with the defaults documented in M4dSettings. */
M4D_API void m4d_default_settings(M4dSettings* s);

/* Creates a decoder. On success *c_out is the new context and 0 is returned; on failure
 * *c_out is NULL. Fails with M4D_ERR_INVALID_ARG for NULL arguments, layers outside
 * M4D_LAYER_ALL or zero, non-zero reserved bytes, or only one of alloc/free set. */
M4D_API int m4d_open(M4dContext** c_out, const M4dSettings* s);

/* Reads a packet header at data (size bytes available) and checks its sync word and header
 * CRC. Use it to split a byte stream into packets: the next packet starts at
 * data + info->packet_size. Returns M4D_ERR_AGAIN when fewer than 24 bytes (or than the whole
 * packet) are available, M4D_ERR_BITSTREAM or M4D_ERR_CHECKSUM for a damaged header,
 * M4D_ERR_LIMIT for a payload size above the specification's limit. After a damaged header,
 * search forward for the next header that parses and call m4d_flush: the skipped bytes may
 * have held a packet whose loss the decoder cannot notice (KEYFRAME_STATIC is optional).
 * After m4d_send_packet fails, search from data + 24: a damaged payload's size may be wrong. */
M4D_API int m4d_parse_packet_header(const uint8_t* data, size_t size, M4dPacketInfo* info);

/* Finds the first offset in data where a packet header parses (m4d_parse_packet_header), to
 * resynchronise after damage. Returns 0 with the header at data + *offset and its packet
 * complete; M4D_ERR_AGAIN when more data is needed: a header was found at *offset but its
 * packet is incomplete (info->packet_size > 0), or none starts in the data
 * (info->packet_size = 0; the first *offset bytes hold no packet start and can be dropped);
 * M4D_ERR_INVALID_ARG for NULL arguments. */
M4D_API int m4d_find_packet(const uint8_t* data, size_t size, size_t* offset, M4dPacketInfo* info);

/* Finds where to start decoding to reach frame `frame_index`, for seeking: scans `data` (a
 * stream from its start, or from any packet boundary) and returns 0 with *offset, the byte
 * offset of the SEQUENCE_HEADER of the last random-access GOP that starts at or before the
 * frame, and *start_frame, that GOP's first frame. Call m4d_flush, send packets from
 * data + *offset, and drop the frames that come before frame_index in stream order; frame
 * numbers wrap at 2^32, so compare (index - *start_frame) with (frame_index - *start_frame)
 * in uint32_t arithmetic, not the numbers themselves. Returns M4D_ERR_AGAIN when no packet
 * of frame_index is in data (a complete stream then does not hold that frame; a partial one
 * may, later), M4D_ERR_BITSTREAM when packets of the frame are found but no random-access GOP
 * starts before them, M4D_ERR_INVALID_ARG for NULL pointers. Damaged bytes are skipped as
 * m4d_find_packet does. */
M4D_API int m4d_find_random_access(const uint8_t* data, size_t size, uint32_t frame_index,
                                   size_t* offset, uint32_t* start_frame);

/* Sends one whole packet (header and payload, exactly size bytes) to the decoder. The data is
 * not retained after the call. Returns:
 *   0                 the packet was consumed (a frame may now be ready);
 *   M4D_ERR_AGAIN     a decoded frame is waiting: call m4d_get_frame, then send this packet
 *                     again (it was not consumed);
 *   negative          the packet was rejected (see m4d_error_string and the logger); a
 *                     caller may simply continue sending. A damaged payload (its CRC or
 *                     syntax) of a static or dynamic packet loses that layer only: decoding
 *                     goes on, every frame is output and the lost layer is concealed and
 *                     flagged (M4dFrame.concealed_layers) until the stream restores it; the
 *                     rejected packet may itself have completed a frame, so call
 *                     m4d_get_frame. After any other error the decoder skips packets until
 *                     the next SEQUENCE_HEADER, except that a SEQUENCE_HEADER that arrives
 *                     inside a frame gives M4D_ERR_BITSTREAM for the frame it cuts (which is
 *                     dropped) but is itself consumed, so decoding goes on. */
M4D_API int m4d_send_packet(M4dContext* c, const uint8_t* data, size_t size);

/* m4d_send_packet with props that come back in M4dFrame.props of the frame this packet
 * completes (NULL: the defaults). Initialise props with m4d_default_data_props: non-zero
 * reserved bytes give M4D_ERR_INVALID_ARG (the packet is not consumed). */
M4D_API int m4d_send_packet_props(M4dContext* c, const uint8_t* data, size_t size,
                                  const M4dDataProps* props);

/* Fills *props with the defaults documented in M4dDataProps. */
M4D_API void m4d_default_data_props(M4dDataProps* props);

/* Fills *info with what the decoder knows of the stream. Returns M4D_ERR_AGAIN before the
 * first SEQUENCE_HEADER was decoded (info is then zeroed), M4D_ERR_INVALID_ARG for NULL
 * pointers. */
M4D_API int m4d_get_stream_info(const M4dContext* c, M4dStreamInfo* info);

/* Takes the next decoded frame. Returns 0 and fills *out, or M4D_ERR_AGAIN when no frame is
 * ready (send more packets). The caller owns the frame until m4d_frame_unref. */
M4D_API int m4d_get_frame(M4dContext* c, M4dFrame* out);

/* Drops all decoding state and any pending frame, for seeking: after a flush the decoder
 * skips packets until the next SEQUENCE_HEADER (a random-access GOP's start). The caller background
 * (m4d_set_background) and the settings are kept. */
M4D_API void m4d_flush(M4dContext* c);

/* Replaces the static layer of every frame by a copy of *background (a caller's own scene),
 * from the next frame on; KEYFRAME_STATIC and STATIC_UPDATE packets are then skipped. NULL
 * restores the stream's own static layer; if a static packet was skipped meanwhile, that
 * layer is empty until the next SEQUENCE_HEADER (spec 6.6). Its sh_degree may differ from
 * the stream's. Returns
 * M4D_ERR_INVALID_ARG for a NULL context, inconsistent arrays or a count above the limit. */
M4D_API int m4d_set_background(M4dContext* c, const M4dGaussians* background);

/* Returns the last error message of the context (empty when none). Valid until the next call
 * on the context. */
M4D_API const char* m4d_last_error(const M4dContext* c);

/* Releases a frame from m4d_get_frame and zeroes *frame. Safe on a zeroed frame. */
M4D_API void m4d_frame_unref(M4dFrame* frame);

/* Computes the normative frame hash (bitstream-spec section 7): MD5 of the output state. */
M4D_API int m4d_frame_hash(const M4dFrame* frame, uint8_t md5[16]);

/* Closes the decoder and sets *c to NULL. Safe on NULL and on *c == NULL. */
M4D_API void m4d_close(M4dContext** c);

#ifdef __cplusplus
}
#endif

#endif /* M4D_M4D_H_ */
