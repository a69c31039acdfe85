// Encoding of symbol_block(count) (bitstream-spec 5.1, 5.2): builds a frequency table from
// the values, normalises it to 2^15, writes the table and the rANS payload.
#ifndef M4D_ENCODER_ENTROPY_SYMBOL_BLOCK_WRITER_H_
#define M4D_ENCODER_ENTROPY_SYMBOL_BLOCK_WRITER_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {

// Normalises symbol counts to frequencies summing to 2^15, every used symbol getting at
// least 1, close to minimum coded size. counts.size() is the alphabet size (>= 1).
std::vector<uint32_t> NormalizeFrequencies(const std::vector<uint64_t>& counts);

// rANS-encodes symbols (each < freqs.size(), with freqs[s] > 0) into the spec's payload with
// `states` interleaved states (1 or kRansInterleavedStates).
std::vector<uint8_t> RansEncode(const uint32_t* symbols, size_t count,
                                const std::vector<uint32_t>& freqs, uint32_t states = 1);

// Writes symbol_block(count) for the values, its payload laid out as `layout` says for that
// count. Fails with M4D_ERR_LIMIT if max - min + 1 exceeds the alphabet limit (4096) or a
// value's magnitude exceeds 2^23.
Status WriteSymbolBlock(const int32_t* values, size_t count, RansLayout layout, ByteWriter* out);

// Size in bytes WriteSymbolBlock would produce (for rate reports and decisions).
size_t SymbolBlockSize(const int32_t* values, size_t count, RansLayout layout);

}  // namespace m4d

#endif  // M4D_ENCODER_ENTROPY_SYMBOL_BLOCK_WRITER_H_
