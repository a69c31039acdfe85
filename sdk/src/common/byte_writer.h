// ByteWriter: little-endian serialisation into a growing buffer, the mirror of ByteReader.
#ifndef M4D_SDK_COMMON_BYTE_WRITER_H_
#define M4D_SDK_COMMON_BYTE_WRITER_H_

#include <cstdint>
#include <cstring>
#include <vector>

namespace m4d {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<uint8_t>* out) : out_(out) {}

  void WriteU8(uint8_t v) { out_->push_back(v); }
  void WriteU16(uint16_t v) {
    WriteU8(static_cast<uint8_t>(v));
    WriteU8(static_cast<uint8_t>(v >> 8));
  }
  void WriteU32(uint32_t v) {
    for (int i = 0; i < 4; ++i) WriteU8(static_cast<uint8_t>(v >> (8 * i)));
  }
  void WriteF32(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    WriteU32(bits);
  }
  void WriteVarUint(uint32_t v) {
    while (v >= 0x80) {
      WriteU8(static_cast<uint8_t>(v | 0x80));
      v >>= 7;
    }
    WriteU8(static_cast<uint8_t>(v));
  }
  void WriteVarSint(int32_t v) {
    WriteVarUint((static_cast<uint32_t>(v) << 1) ^ static_cast<uint32_t>(v >> 31));
  }
  void WriteBytes(const uint8_t* data, size_t n) { out_->insert(out_->end(), data, data + n); }
  void WriteBytes(const std::vector<uint8_t>& data) { WriteBytes(data.data(), data.size()); }

  size_t size() const { return out_->size(); }
  std::vector<uint8_t>* buffer() { return out_; }

 private:
  std::vector<uint8_t>* out_;
};

}  // namespace m4d

#endif  // M4D_SDK_COMMON_BYTE_WRITER_H_
