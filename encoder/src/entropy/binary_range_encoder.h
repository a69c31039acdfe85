// Adaptive binary range coding (bitstream-spec 5.7, version 0.8): the encoder of LZMA's range
// coder, the inverse of the SDK's BinaryRangeDecoder.
#ifndef M4D_ENCODER_ENTROPY_BINARY_RANGE_ENCODER_H_
#define M4D_ENCODER_ENTROPY_BINARY_RANGE_ENCODER_H_

#include <cstdint>
#include <vector>

#include "sdk/src/entropy/binary_range_decoder.h"

namespace m4d {

class BinaryRangeEncoder {
 public:
  // Codes `bit` with the adaptive probability `p` (which adapts as the decoder's does).
  void EncodeBit(BitProbability* p, int bit);
  // Codes `bit` with probability one half.
  void EncodeBypassBit(int bit);
  // Flushes the coder and returns the payload, which the decoder reads exactly to its end.
  std::vector<uint8_t> Finish();

 private:
  void ShiftLow();
  void Normalize();

  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
  std::vector<uint8_t> bytes_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_ENTROPY_BINARY_RANGE_ENCODER_H_
