// The stream's frame rate (fps_num / fps_den in the sequence header) from what a user types
// or what a capture records.
#ifndef M4D_ENCODER_STREAM_FRAME_RATE_H_
#define M4D_ENCODER_STREAM_FRAME_RATE_H_

#include <cstdint>
#include <string>

#include "sdk/src/common/status.h"

namespace m4d {

// The rate when neither the user nor the capture gives one (N3DV's and Panoptic's 30).
constexpr uint32_t kDefaultFps = 30;

// "30", "29.97" (read as 30000/1001 when within 1e-3 of an NTSC rate N * 1000 / 1001, else
// to 1/1000) or "30000/1001". Both terms in 1..2^31 as the header allows; otherwise
// M4D_ERR_INVALID_ARG naming the text.
Status ParseFrameRate(const std::string& text, uint32_t* num, uint32_t* den);

}  // namespace m4d

#endif  // M4D_ENCODER_STREAM_FRAME_RATE_H_
