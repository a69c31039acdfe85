// libFuzzer target for symbol_block() (frequency table and rANS, bitstream-spec 5.1, 5.2):
// the first two bytes give the count (13 bits) and the layout (bit 15: one state, else
// interleaved states from 4096 values), the rest is the block. Decoded values stay in range.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/entropy/symbol_block_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const uint32_t count = data[0] | (data[1] & 0x1f) << 8;
  std::vector<int32_t> values(count);
  const m4d::RansLayout layout =
      data[1] & 0x80 ? m4d::RansLayout::kSingleState : m4d::RansLayout::kInterleaved;
  m4d::ByteReader reader(data + 2, size - 2);
  if (m4d::ReadSymbolBlock(&reader, layout, count, -32768, 32767, values.data()).ok()) {
    for (int32_t v : values) {
      if (v < -32768 || v > 32767) std::abort();
    }
  }
  return 0;
}
