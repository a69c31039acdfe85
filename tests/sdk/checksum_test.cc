#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sdk/src/common/crc32.h"
#include "sdk/src/common/md5.h"

namespace m4d {
namespace {

uint32_t Crc32Of(const std::string& s) {
  return Crc32(reinterpret_cast<const uint8_t*>(s.data()), s.size());
}

// Bit-at-a-time CRC-32/ISO-HDLC straight from the definition (spec 5.3), as a reference for
// the table-driven implementation.
uint32_t BitwiseCrc32(const uint8_t* data, size_t size) {
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
  }
  return crc ^ 0xFFFFFFFFu;
}

std::string Md5Hex(const std::string& s) {
  Md5 md5;
  md5.Update(s.data(), s.size());
  uint8_t digest[16];
  md5.Final(digest);
  return HexDigest(digest);
}

// Feeds the message in chunks of the given sizes, cycling through them.
std::string Md5HexChunked(const std::string& s, const std::vector<size_t>& chunks) {
  Md5 md5;
  size_t pos = 0;
  for (size_t k = 0; pos < s.size(); ++k) {
    const size_t take = std::min(chunks[k % chunks.size()], s.size() - pos);
    md5.Update(s.data() + pos, take);
    pos += take;
  }
  uint8_t digest[16];
  md5.Final(digest);
  return HexDigest(digest);
}

std::string PatternString(size_t n) {
  std::string s(n, '\0');
  for (size_t i = 0; i < n; ++i) s[i] = static_cast<char>((i * 7 + 3) & 255);
  return s;
}

TEST(ChecksumTest, Crc32CheckValue) {
  EXPECT_EQ(Crc32Of("123456789"), 0xCBF43926u);
  EXPECT_EQ(Crc32Of("The quick brown fox jumps over the lazy dog"), 0x414FA339u);
}

TEST(ChecksumTest, Crc32OfNothingIsZero) {
  EXPECT_EQ(Crc32(nullptr, 0), 0u);
  EXPECT_EQ(Crc32Of(""), 0u);
}

TEST(ChecksumTest, Crc32KnownLongInput) {
  std::vector<uint8_t> data(1024);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i);
  EXPECT_EQ(Crc32(data.data(), data.size()), 0xB70B4C26u);
}

TEST(ChecksumTest, Crc32MatchesBitwiseAtEveryLengthAndAlignment) {
  std::mt19937 rng(7);
  std::vector<uint8_t> data(300);
  for (auto& b : data) b = static_cast<uint8_t>(rng());
  for (size_t offset = 0; offset < 8; ++offset) {
    for (size_t size = 0; offset + size <= 200; ++size) {
      ASSERT_EQ(Crc32(data.data() + offset, size), BitwiseCrc32(data.data() + offset, size))
          << "offset " << offset << " size " << size;
    }
  }
}

TEST(ChecksumTest, Crc32DetectsEverySingleBitFlip) {
  std::vector<uint8_t> data(64);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 31);
  const uint32_t crc = Crc32(data.data(), data.size());
  for (size_t bit = 0; bit < data.size() * 8; ++bit) {
    data[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_NE(Crc32(data.data(), data.size()), crc) << "bit " << bit;
    data[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
  }
}

TEST(ChecksumTest, Md5Rfc1321TestSuite) {
  EXPECT_EQ(Md5Hex(""), "d41d8cd98f00b204e9800998ecf8427e");
  EXPECT_EQ(Md5Hex("a"), "0cc175b9c0f1b6a831c399e269772661");
  EXPECT_EQ(Md5Hex("abc"), "900150983cd24fb0d6963f7d28e17f72");
  EXPECT_EQ(Md5Hex("message digest"), "f96b697d7cb7938d525a2f31aaf161d0");
  EXPECT_EQ(Md5Hex("abcdefghijklmnopqrstuvwxyz"), "c3fcd3d76192e4007dfb496cca67e13b");
  EXPECT_EQ(Md5Hex("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"),
            "d174ab98d277d9f5a5611c2c9f419d9f");
  EXPECT_EQ(Md5Hex("1234567890123456789012345678901234567890"
                   "1234567890123456789012345678901234567890"),
            "57edf4a22be3c955ac49da2e2107b67a");
}

// Lengths around the padding boundaries (56 and 64 bytes mod 64); digests from Python hashlib.
TEST(ChecksumTest, Md5PaddingBoundaries) {
  const std::pair<size_t, const char*> cases[] = {
      {55, "52c0e574e1198de5fe3f8f11440dcb1b"},  {56, "46c9907fc908ee68b1e7b8e71286a518"},
      {57, "1c805dd236c35cab25fcb1bc73802c51"},  {63, "a62f6d59e837867693f042f5b8f5a236"},
      {64, "7160b8fb5e9e4023d549c3971fbaeead"},  {65, "70bd662e7aefbda85a0f7244167b7897"},
      {119, "e84905d4214f4d1ca56c2cdcc152b143"}, {120, "e3eb5a6c8669ea01a8c185b8abc8a5dc"},
      {128, "10b2da1a82f16d99a81a7203fe9f02cb"},
  };
  for (const auto& [size, hex] : cases) EXPECT_EQ(Md5Hex(PatternString(size)), hex) << size;
}

TEST(ChecksumTest, Md5MillionA) {
  EXPECT_EQ(Md5Hex(std::string(1000000, 'a')), "7707d6ae4e027c70eea2a935c2296f21");
}

TEST(ChecksumTest, Md5SplitUpdatesMatchOneShot) {
  const std::string messages[] = {
      "message digest",
      "1234567890123456789012345678901234567890"
      "1234567890123456789012345678901234567890",
      PatternString(1000),
  };
  const std::vector<std::vector<size_t>> splits = {{1},  {3},         {7, 1},   {63},
                                                   {65}, {13, 64, 5}, {0, 2, 0}};
  for (const std::string& message : messages) {
    const std::string expected = Md5Hex(message);
    for (const auto& chunks : splits) EXPECT_EQ(Md5HexChunked(message, chunks), expected);
    // Every single split point.
    for (size_t cut = 0; cut <= message.size(); ++cut) {
      Md5 md5;
      md5.Update(message.data(), cut);
      md5.Update(message.data() + cut, message.size() - cut);
      uint8_t digest[16];
      md5.Final(digest);
      ASSERT_EQ(HexDigest(digest), expected) << "cut " << cut;
    }
  }
}

TEST(ChecksumTest, Md5IsReusableAfterFinal) {
  Md5 md5;
  uint8_t digest[16];
  md5.Update("abc", 3);
  md5.Final(digest);
  EXPECT_EQ(HexDigest(digest), "900150983cd24fb0d6963f7d28e17f72");
  md5.Update("message digest", 14);
  md5.Final(digest);
  EXPECT_EQ(HexDigest(digest), "f96b697d7cb7938d525a2f31aaf161d0");
}

TEST(ChecksumTest, HexDigestIsLowercase) {
  uint8_t digest[16];
  for (int i = 0; i < 16; ++i) digest[i] = static_cast<uint8_t>(i * 17);
  EXPECT_EQ(HexDigest(digest), "00112233445566778899aabbccddeeff");
}

}  // namespace
}  // namespace m4d
