// MD5 (RFC 1321), used for the normative frame hash (bitstream-spec section 7).
#ifndef M4D_SDK_COMMON_MD5_H_
#define M4D_SDK_COMMON_MD5_H_

#include <cstddef>
#include <cstdint>
#include <string>

namespace m4d {

class Md5 {
 public:
  Md5();
  void Update(const void* data, size_t size);
  void Final(uint8_t digest[16]);

 private:
  void Transform(const uint8_t block[64]);
  uint32_t state_[4];
  uint64_t length_ = 0;
  uint8_t buffer_[64];
  size_t buffered_ = 0;
};

std::string HexDigest(const uint8_t digest[16]);

}  // namespace m4d

#endif  // M4D_SDK_COMMON_MD5_H_
