// Packet header (bitstream-spec section 3): 24 bytes in front of every payload.
#ifndef M4D_SDK_BITSTREAM_PACKET_HEADER_H_
#define M4D_SDK_BITSTREAM_PACKET_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

constexpr uint8_t kPacketSync[4] = {'M', '4', 'D', 'P'};
constexpr uint8_t kFlagEndOfFrame = 1;

struct PacketHeader {
  uint8_t type = 0;
  uint8_t flags = 0;
  uint32_t frame_index = 0;
  uint32_t payload_size = 0;
  uint32_t payload_crc = 0;

  bool end_of_frame() const { return (flags & kFlagEndOfFrame) != 0; }
};

// Parses the header at data[0..24): sync word, header CRC, reserved bits, payload size limit.
// Needs size >= kPacketHeaderSize (else M4D_ERR_AGAIN). Does not look at the payload.
Status ParsePacketHeader(const uint8_t* data, size_t size, PacketHeader* out);

// Serialises a header for `payload` (computing both CRCs) in front of it, appended to *out.
void AppendPacket(uint8_t type, uint32_t frame_index, bool end_of_frame, const uint8_t* payload,
                  size_t payload_size, std::vector<uint8_t>* out);

}  // namespace m4d

#endif  // M4D_SDK_BITSTREAM_PACKET_HEADER_H_
