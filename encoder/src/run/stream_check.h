// The closed loop seen from outside: a written stream decoded with the SDK's public API must
// give, frame by frame, the hashes of the encoder's reconstruction. Also what decoding each
// frame costs, for `m4d bench`.
#ifndef M4D_ENCODER_RUN_STREAM_CHECK_H_
#define M4D_ENCODER_RUN_STREAM_CHECK_H_

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/pipeline/frame_report.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct DecodedStream {
  std::vector<std::string> hashes;  // per frame (bitstream-spec 7), hex
  std::vector<double> seconds;      // per frame: its packets sent and the frame taken out
};

// Decodes the whole stream through m4d.h, packet by packet as a player would.
Status DecodeStream(const std::vector<uint8_t>& stream, DecodedStream* decoded);

// M4D_ERR_BITSTREAM naming the first frame that differs (or a count mismatch).
Status CheckDecodedHashes(const std::vector<uint8_t>& stream, const SequenceReport& report);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_STREAM_CHECK_H_
