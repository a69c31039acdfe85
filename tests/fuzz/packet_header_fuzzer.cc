// libFuzzer target for the packet layer: the packet header parser and the resynchronising
// search over arbitrary bytes, and the SEQUENCE_HEADER payload parser. Whatever they accept
// must be self-consistent: a packet that parses fits in the input, a found packet starts
// where a header parses.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "m4d/m4d.h"
#include "sdk/src/bitstream/sequence_header.h"
#include "sdk/src/common/byte_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  M4dPacketInfo info;
  if (m4d_parse_packet_header(data, size, &info) == M4D_OK && info.packet_size > size) {
    std::abort();
  }
  size_t offset = 0;
  const int found = m4d_find_packet(data, size, &offset, &info);
  if (offset > size) std::abort();
  if (found == M4D_OK && (m4d_parse_packet_header(data + offset, size - offset, &info) != M4D_OK ||
                          offset + info.packet_size > size)) {
    std::abort();
  }
  m4d::ByteReader reader(data, size);
  m4d::SequenceHeader header;
  if (m4d::ReadSequenceHeader(&reader, 1u << 24, &header).ok() &&
      header.grid.total_values() > (1u << 24)) {
    std::abort();
  }
  return 0;
}
