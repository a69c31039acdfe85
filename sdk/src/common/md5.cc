#include "sdk/src/common/md5.h"

#include <cstring>

#include "sdk/src/common/byte_reader.h"

namespace m4d {
namespace {

// floor(2^32 * |sin(i + 1)|), RFC 1321 section 3.4.
constexpr uint32_t kSine[64] = {
    0xd76aa478, 0xe8c7b756, 0x242070db, 0xc1bdceee, 0xf57c0faf, 0x4787c62a, 0xa8304613, 0xfd469501,
    0x698098d8, 0x8b44f7af, 0xffff5bb1, 0x895cd7be, 0x6b901122, 0xfd987193, 0xa679438e, 0x49b40821,
    0xf61e2562, 0xc040b340, 0x265e5a51, 0xe9b6c7aa, 0xd62f105d, 0x02441453, 0xd8a1e681, 0xe7d3fbc8,
    0x21e1cde6, 0xc33707d6, 0xf4d50d87, 0x455a14ed, 0xa9e3e905, 0xfcefa3f8, 0x676f02d9, 0x8d2a4c8a,
    0xfffa3942, 0x8771f681, 0x6d9d6122, 0xfde5380c, 0xa4beea44, 0x4bdecfa9, 0xf6bb4b60, 0xbebfbc70,
    0x289b7ec6, 0xeaa127fa, 0xd4ef3085, 0x04881d05, 0xd9d4d039, 0xe6db99e5, 0x1fa27cf8, 0xc4ac5665,
    0xf4292244, 0x432aff97, 0xab9423a7, 0xfc93a039, 0x655b59c3, 0x8f0ccc92, 0xffeff47d, 0x85845dd1,
    0x6fa87e4f, 0xfe2ce6e0, 0xa3014314, 0x4e0811a1, 0xf7537e82, 0xbd3af235, 0x2ad7d2bb, 0xeb86d391};

inline uint32_t RotateLeft(uint32_t v, int s) { return (v << s) | (v >> (32 - s)); }

// The four auxiliary functions of RFC 1321 section 3.4.
struct RoundF {
  static uint32_t Apply(uint32_t x, uint32_t y, uint32_t z) { return (x & y) | (~x & z); }
};
struct RoundG {
  static uint32_t Apply(uint32_t x, uint32_t y, uint32_t z) { return (x & z) | (y & ~z); }
};
struct RoundH {
  static uint32_t Apply(uint32_t x, uint32_t y, uint32_t z) { return x ^ y ^ z; }
};
struct RoundI {
  static uint32_t Apply(uint32_t x, uint32_t y, uint32_t z) { return y ^ (x | ~z); }
};

// a = b + ((a + F(b, c, d) + X[k] + T[i]) <<< s).
template <typename Fn, int kShift>
inline void Step(uint32_t& a, uint32_t b, uint32_t c, uint32_t d, uint32_t x, uint32_t t) {
  a = b + RotateLeft(a + Fn::Apply(b, c, d) + x + t, kShift);
}

// One round: 16 steps, four at a time so the register roles and shifts are compile-time.
// Message word of step i is x[(start + stride * i) % 16].
template <typename Fn, int kS0, int kS1, int kS2, int kS3>
inline void Round(uint32_t* h, const uint32_t* x, int round, int start, int stride) {
  uint32_t a = h[0], b = h[1], c = h[2], d = h[3];
  const uint32_t* t = kSine + 16 * round;
  for (int i = 0; i < 16; i += 4) {
    Step<Fn, kS0>(a, b, c, d, x[(start + stride * i) & 15], t[i]);
    Step<Fn, kS1>(d, a, b, c, x[(start + stride * (i + 1)) & 15], t[i + 1]);
    Step<Fn, kS2>(c, d, a, b, x[(start + stride * (i + 2)) & 15], t[i + 2]);
    Step<Fn, kS3>(b, c, d, a, x[(start + stride * (i + 3)) & 15], t[i + 3]);
  }
  h[0] = a;
  h[1] = b;
  h[2] = c;
  h[3] = d;
}

constexpr uint32_t kInitialState[4] = {0x67452301, 0xefcdab89, 0x98badcfe, 0x10325476};

}  // namespace

Md5::Md5() { std::memcpy(state_, kInitialState, sizeof(state_)); }

void Md5::Transform(const uint8_t block[64]) {
  uint32_t x[16];
  for (int i = 0; i < 16; ++i) x[i] = ByteReader::LoadU32(block + 4 * i);
  uint32_t h[4] = {state_[0], state_[1], state_[2], state_[3]};
  Round<RoundF, 7, 12, 17, 22>(h, x, 0, 0, 1);
  Round<RoundG, 5, 9, 14, 20>(h, x, 1, 1, 5);
  Round<RoundH, 4, 11, 16, 23>(h, x, 2, 5, 3);
  Round<RoundI, 6, 10, 15, 21>(h, x, 3, 0, 7);
  for (int i = 0; i < 4; ++i) state_[i] += h[i];
}

void Md5::Update(const void* data, size_t size) {
  const uint8_t* p = static_cast<const uint8_t*>(data);
  length_ += size;
  if (buffered_ > 0) {
    const size_t take = size < 64 - buffered_ ? size : 64 - buffered_;
    std::memcpy(buffer_ + buffered_, p, take);
    buffered_ += take;
    p += take;
    size -= take;
    if (buffered_ < 64) return;
    Transform(buffer_);
    buffered_ = 0;
  }
  for (; size >= 64; p += 64, size -= 64) Transform(p);
  std::memcpy(buffer_, p, size);
  buffered_ = size;
}

void Md5::Final(uint8_t digest[16]) {
  const uint64_t bit_length = length_ * 8;
  // Padding: 0x80, zeros up to 56 mod 64, then the message length in bits (64-bit LE).
  uint8_t pad[72] = {0x80};
  const size_t pad_size = (buffered_ < 56 ? 56 : 120) - buffered_;
  for (int i = 0; i < 8; ++i) pad[pad_size + i] = static_cast<uint8_t>(bit_length >> (8 * i));
  Update(pad, pad_size + 8);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) digest[4 * i + j] = static_cast<uint8_t>(state_[i] >> (8 * j));
  }
  // Ready for the next message.
  std::memcpy(state_, kInitialState, sizeof(state_));
  length_ = 0;
  buffered_ = 0;
}

std::string HexDigest(const uint8_t digest[16]) {
  static const char kHex[] = "0123456789abcdef";
  std::string hex(32, '0');
  for (int i = 0; i < 16; ++i) {
    hex[2 * i] = kHex[digest[i] >> 4];
    hex[2 * i + 1] = kHex[digest[i] & 15];
  }
  return hex;
}

}  // namespace m4d
