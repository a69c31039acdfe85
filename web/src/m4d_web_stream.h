// The WebAssembly module's stream reader (m4d_web_stream.cc), shared with its renderer
// binding (m4d_web_renderer.cc), which draws the frame the reader holds.
#ifndef M4D_WEB_M4D_WEB_STREAM_H_
#define M4D_WEB_M4D_WEB_STREAM_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "m4d/m4d.h"

// A stream being read: its bytes, the reading position, its decoder and the frame handed out.
struct M4dWebStream {
  M4dContext* context = nullptr;
  std::vector<uint8_t> bytes;  // everything received, kept for seeking
  size_t position = 0;         // the next packet (or where a resynchronisation resumes)
  bool resynchronising = false;
  bool ended = false;
  bool inside_frame = false;  // the last packet header read has no end_of_frame
  // After a seek, the frames before seek_target are dropped. Frame numbers wrap at 2^32: a
  // frame is placed by its distance from seek_start, the random-access frame decoding restarts at.
  bool seeking = false;
  uint32_t seek_start = 0;
  uint32_t seek_target = 0;
  M4dFrame frame = {};
  bool holding_frame = false;
  int error_count = 0;
  int first_error_code = 0;
  size_t skipped_bytes = 0;
  size_t last_error_offset = 0;
  int last_error_code = 0;
  std::string last_error_message;
};

#endif  // M4D_WEB_M4D_WEB_STREAM_H_
