// CRC-32/ISO-HDLC (bitstream-spec 5.3), the checksum of packet headers and payloads.
#ifndef M4D_SDK_COMMON_CRC32_H_
#define M4D_SDK_COMMON_CRC32_H_

#include <cstddef>
#include <cstdint>

namespace m4d {

uint32_t Crc32(const uint8_t* data, size_t size);

}  // namespace m4d

#endif  // M4D_SDK_COMMON_CRC32_H_
