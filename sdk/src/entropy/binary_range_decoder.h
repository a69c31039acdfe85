// Decoding of adaptive binary range coding (bitstream-spec 5.7, version 0.8): LZMA's range
// coder, bits coded with 12-bit probabilities that adapt after every bit, or with probability
// one half (bypass bits).
#ifndef M4D_SDK_ENTROPY_BINARY_RANGE_DECODER_H_
#define M4D_SDK_ENTROPY_BINARY_RANGE_DECODER_H_

#include <cstddef>
#include <cstdint>

#include "sdk/src/common/spec_limits.h"

namespace m4d {

// A bit's adaptive probability of being 0, in units of 2^-kRangeProbabilityBits.
using BitProbability = uint16_t;

// Moves the probability towards the bit just coded (shared by the decoder and the encoder).
inline void AdaptBitProbability(int bit, BitProbability* p) {
  if (bit == 0) {
    *p = static_cast<BitProbability>(*p +
                                     (((1u << kRangeProbabilityBits) - *p) >> kRangeAdaptShift));
  } else {
    *p = static_cast<BitProbability>(*p - (*p >> kRangeAdaptShift));
  }
}

class BinaryRangeDecoder {
 public:
  // Starts decoding `size` payload bytes (at least 4, else overran() is true at once).
  BinaryRangeDecoder(const uint8_t* data, size_t size) : data_(data), end_(data + size) {
    for (int k = 0; k < 4; ++k) code_ = (code_ << 8) | NextByte();
  }

  // Without branches on the bit: the bits of attribute values are close to unpredictable, and
  // a mispredicted branch per bit cost twice the decoding time.
  int DecodeBit(BitProbability* p) {
    const uint32_t probability = *p;
    const uint32_t bound = (range_ >> kRangeProbabilityBits) * probability;
    const uint32_t bit = code_ >= bound ? 1u : 0u;
    const uint32_t mask = 0u - bit;
    code_ -= bound & mask;
    range_ = (bound & ~mask) | ((range_ - bound) & mask);
    const uint32_t toward_zero = ((1u << kRangeProbabilityBits) - probability) >> kRangeAdaptShift;
    const uint32_t toward_one = probability >> kRangeAdaptShift;
    *p = static_cast<BitProbability>(probability + (toward_zero & ~mask) - (toward_one & mask));
    Normalize();
    return static_cast<int>(bit);
  }

  int DecodeBypassBit() {
    range_ >>= 1;
    const uint32_t bit = code_ >= range_ ? 1u : 0u;
    code_ -= range_ & (0u - bit);
    Normalize();
    return static_cast<int>(bit);
  }

  // True when decoding needed bytes past the payload's end (spec 5.7: M4D_ERR_BITSTREAM).
  bool overran() const { return overran_; }
  // True when every payload byte was read, and none past the end.
  bool consumed_exactly() const { return !overran_ && data_ == end_; }

 private:
  uint8_t NextByte() {
    if (data_ == end_) {
      overran_ = true;
      return 0;
    }
    return *data_++;
  }
  void Normalize() {
    while (range_ < kRangeTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | NextByte();
    }
  }

  const uint8_t* data_;
  const uint8_t* end_;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  bool overran_ = false;
};

}  // namespace m4d

#endif  // M4D_SDK_ENTROPY_BINARY_RANGE_DECODER_H_
