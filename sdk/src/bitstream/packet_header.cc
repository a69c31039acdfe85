#include "sdk/src/bitstream/packet_header.h"

#include <cstring>
#include <string>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/crc32.h"
#include "sdk/src/common/spec_limits.h"

namespace m4d {

Status ParsePacketHeader(const uint8_t* data, size_t size, PacketHeader* out) {
  if (size < kPacketHeaderSize) return Status(M4D_ERR_AGAIN, "packet header: need 24 bytes");
  if (std::memcmp(data, kPacketSync, 4) != 0) return BitstreamError("packet header: no sync word");
  const uint32_t header_crc = ByteReader::LoadU32(data + 20);
  if (Crc32(data, 20) != header_crc) {
    return Status(M4D_ERR_CHECKSUM, "packet header: CRC mismatch");
  }
  ByteReader reader(data + 4, 16);
  uint16_t reserved = 0;
  reader.ReadU8(&out->type);
  reader.ReadU8(&out->flags);
  reader.ReadU16(&reserved);
  reader.ReadU32(&out->frame_index);
  reader.ReadU32(&out->payload_size);
  reader.ReadU32(&out->payload_crc);
  if (reserved != 0 || (out->flags & ~kFlagEndOfFrame) != 0) {
    return BitstreamError("packet header: reserved bits set");
  }
  if (out->payload_size > kMaxPayloadSize) {
    return LimitError("packet header: payload size " + std::to_string(out->payload_size) +
                      " above the limit of 2^26 bytes");
  }
  return Status::Ok();
}

void AppendPacket(uint8_t type, uint32_t frame_index, bool end_of_frame, const uint8_t* payload,
                  size_t payload_size, std::vector<uint8_t>* out) {
  const size_t start = out->size();
  ByteWriter writer(out);
  writer.WriteBytes(kPacketSync, 4);
  writer.WriteU8(type);
  writer.WriteU8(end_of_frame ? kFlagEndOfFrame : 0);
  writer.WriteU16(0);
  writer.WriteU32(frame_index);
  writer.WriteU32(static_cast<uint32_t>(payload_size));
  writer.WriteU32(Crc32(payload, payload_size));
  writer.WriteU32(Crc32(out->data() + start, 20));
  writer.WriteBytes(payload, payload_size);
}

}  // namespace m4d
