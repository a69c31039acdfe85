// Decoding of symbol_block(count) (bitstream-spec 5.1, 5.2): a transmitted frequency table
// followed by an rANS payload.
#ifndef M4D_SDK_ENTROPY_SYMBOL_BLOCK_READER_H_
#define M4D_SDK_ENTROPY_SYMBOL_BLOCK_READER_H_

#include <cstdint>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/common/status.h"

namespace m4d {

// The rANS payload's layout (spec 5.2): one state before version 0.4; from 0.4 on, blocks of
// kRansInterleaveMinCount values or more interleave kRansInterleavedStates states, so their
// symbols decode as independent chains (about 3x faster on one core).
enum class RansLayout { kSingleState, kInterleaved };

// The number of rANS states of a block of `count` values.
inline uint32_t RansStates(RansLayout layout, uint32_t count) {
  const bool interleave = layout == RansLayout::kInterleaved && count >= kRansInterleaveMinCount;
  return interleave ? kRansInterleavedStates : 1;
}

// Reads a symbol block of `count` values into out[0..count-1]. Every value must lie in
// [lo, hi] (checked once from the block's min and alphabet size, before decoding), otherwise
// M4D_ERR_BITSTREAM. The reader advances past the block.
Status ReadSymbolBlock(ByteReader* reader, RansLayout layout, uint32_t count, int32_t lo,
                       int32_t hi, int32_t* out);

}  // namespace m4d

#endif  // M4D_SDK_ENTROPY_SYMBOL_BLOCK_READER_H_
