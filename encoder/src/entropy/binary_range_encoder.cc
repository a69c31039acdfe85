// The range encoder keeps the interval's low end in 33 bits: a carry out of bit 32 adds one to
// the byte last held back and turns the 0xFF bytes after it into zeros, so it holds back a byte
// and the run of 0xFF bytes after it (cache_, cache_size_) until no carry can reach them.
#include "encoder/src/entropy/binary_range_encoder.h"

namespace m4d {

void BinaryRangeEncoder::EncodeBit(BitProbability* p, int bit) {
  const uint32_t bound = (range_ >> kRangeProbabilityBits) * *p;
  if (bit == 0) {
    range_ = bound;
  } else {
    low_ += bound;
    range_ -= bound;
  }
  AdaptBitProbability(bit, p);
  Normalize();
}

void BinaryRangeEncoder::EncodeBypassBit(int bit) {
  range_ >>= 1;
  if (bit != 0) low_ += range_;
  Normalize();
}

void BinaryRangeEncoder::Normalize() {
  while (range_ < kRangeTop) {
    range_ <<= 8;
    ShiftLow();
  }
}

void BinaryRangeEncoder::ShiftLow() {
  if (static_cast<uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
    const uint8_t carry = static_cast<uint8_t>(low_ >> 32);
    uint8_t held = cache_;
    do {
      bytes_.push_back(static_cast<uint8_t>(held + carry));
      held = 0xFF;
    } while (--cache_size_ != 0);
    cache_ = static_cast<uint8_t>(low_ >> 24);
  }
  ++cache_size_;
  low_ = (low_ & 0x00FFFFFFu) << 8;
}

std::vector<uint8_t> BinaryRangeEncoder::Finish() {
  for (int k = 0; k < 5; ++k) ShiftLow();
  // The first byte is the initial cache, 0: the decoder starts from the four after it.
  bytes_.erase(bytes_.begin());
  return std::move(bytes_);
}

}  // namespace m4d
