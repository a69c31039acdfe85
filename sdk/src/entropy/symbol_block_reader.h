// Decoding of symbol_block(count) (bitstream-spec 5.1, 5.2): a transmitted frequency table
// followed by an rANS payload.
#ifndef M4D_ENTROPY_SYMBOL_BLOCK_READER_H_
#define M4D_ENTROPY_SYMBOL_BLOCK_READER_H_

#include <cstdint>

#include "common/byte_reader.h"
#include "common/status.h"

namespace m4d {

// Reads a symbol block of `count` values into out[0..count-1]. Every value must lie in
// [lo, hi] (checked once from the block's min and alphabet size, before decoding), otherwise
// M4D_ERR_BITSTREAM. The reader advances past the block.
Status ReadSymbolBlock(ByteReader* reader, uint32_t count, int32_t lo, int32_t hi, int32_t* out);

}  // namespace m4d

#endif  // M4D_ENTROPY_SYMBOL_BLOCK_READER_H_
