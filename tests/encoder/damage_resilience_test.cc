// Damage resilience: bytes flipped, dropped or cut at 1000 random places in the conformance
// streams, fed to the SDK the way a player reads a file (PlayBytes: resynchronise on the next
// valid header after damage, spec 3, flushing the decoder when bytes were skipped). The decoder
// must never crash or hang, must report the damage, must output only layers that are exactly
// right or flagged as concealed (spec 6.8), and must decode every GOP that starts after the
// damage. Then a byte of every kind of every packet type is flipped in a multi-GOP stream: a
// damaged payload must cost no frame.
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "encoder/src/synthetic/synthetic_content.h"
#include "tests/encoder/stream_test_util.h"

namespace m4d {
namespace testing {
namespace {

const std::string kDir = std::string(M4D_SOURCE_DIR) + "/conformance/streams/";

struct CleanStream {
  std::string name;
  std::vector<uint8_t> bytes;
  std::map<uint32_t, std::string> expected;  // frame_index -> hash
  // The hashes of one layer alone: a frame whose other layer is concealed hashes as these.
  std::map<uint32_t, std::string> static_only, dynamic_only;
  std::vector<size_t> gop_starts;  // byte offsets of the SEQUENCE_HEADERs (random access)
  std::vector<std::vector<uint32_t>> gop_frames;
};

std::map<uint32_t, std::string> ReadHashes(const std::string& path) {
  std::map<uint32_t, std::string> hashes;
  std::ifstream md5(path);
  uint32_t index = 0;
  std::string hash;
  while (md5 >> index >> hash) hashes[index] = hash;
  return hashes;
}

// What a frame of `clean` hashes as when the layers `concealed` are concealed.
const std::string& ExpectedHash(const CleanStream& clean, uint32_t index, uint32_t concealed) {
  if (concealed == M4D_LAYER_STATIC) return clean.dynamic_only.at(index);
  if (concealed == M4D_LAYER_DYNAMIC) return clean.static_only.at(index);
  static const std::string kNone = [] {
    M4dFrame none{};
    return HashOf(none);
  }();
  return concealed == 0 ? clean.expected.at(index) : kNone;
}

CleanStream LoadBytes(const std::string& name, std::vector<uint8_t> bytes) {
  CleanStream s;
  s.name = name;
  s.bytes = std::move(bytes);
  size_t pos = 0;
  M4dPacketInfo info;
  while (pos < s.bytes.size() &&
         m4d_parse_packet_header(&s.bytes[pos], s.bytes.size() - pos, &info) == M4D_OK) {
    if (info.type == M4D_PACKET_SEQUENCE_HEADER) {
      s.gop_starts.push_back(pos);
      s.gop_frames.emplace_back();
    }
    if (info.end_of_frame && !s.gop_frames.empty()) s.gop_frames.back().push_back(info.frame_index);
    pos += info.packet_size;
  }
  return s;
}

CleanStream Load(const std::string& name) {
  std::ifstream file(kDir + name + ".m4d", std::ios::binary);
  CleanStream s = LoadBytes(name, std::vector<uint8_t>(std::istreambuf_iterator<char>(file), {}));
  s.expected = ReadHashes(kDir + name + ".md5");
  s.static_only = ReadHashes(kDir + name + ".static.md5");
  s.dynamic_only = ReadHashes(kDir + name + ".dynamic.md5");
  return s;
}

std::vector<CleanStream> LoadAll() {
  std::vector<CleanStream> streams;
  if (DIR* dir = opendir(kDir.c_str())) {
    while (dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 4 && name.substr(name.size() - 4) == ".m4d") {
        streams.push_back(Load(name.substr(0, name.size() - 4)));
      }
    }
    closedir(dir);
  }
  std::sort(streams.begin(), streams.end(),
            [](const CleanStream& a, const CleanStream& b) { return a.name < b.name; });
  return streams;
}

enum class Damage { kFlip, kDrop, kTruncate };

TEST(DamageResilience, ThousandRandomDamagesNeverCrashAndResumeAtTheNextGop) {
  const std::vector<CleanStream> streams = LoadAll();
  ASSERT_GE(streams.size(), 4u);
  SyntheticRandom rng(2026);
  int reported = 0, resumed_gops = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const CleanStream& clean = streams[trial % streams.size()];
    const Damage damage = static_cast<Damage>(trial % 3);
    std::vector<uint8_t> bytes = clean.bytes;
    const size_t at = rng.Next() % bytes.size();
    if (damage == Damage::kFlip) bytes[at] ^= static_cast<uint8_t>(1 + rng.Next() % 255);
    if (damage == Damage::kDrop) bytes.erase(bytes.begin() + at);
    if (damage == Damage::kTruncate) bytes.resize(at);
    const PlayResult out = PlayBytes(DefaultSettings(), bytes);
    SCOPED_TRACE(clean.name + " damage " + std::to_string(trial % 3) + " at " + std::to_string(at));
    ASSERT_LE(out.steps, bytes.size() + 1);  // every step moves forward: no hang
    // Only exact layers come out, the others flagged: every damaged packet is caught by a CRC.
    for (size_t i = 0; i < out.frames.size(); ++i) {
      const auto& [index, hash] = out.frames[i];
      ASSERT_EQ(clean.expected.count(index), 1u);
      EXPECT_EQ(hash, ExpectedHash(clean, index, out.concealed[i])) << "frame " << index;
    }
    if (damage != Damage::kTruncate) {
      EXPECT_TRUE(!out.errors.empty() || out.truncated);
    } else {
      // A cut is an incomplete packet, or at a packet boundary frames simply end early.
      EXPECT_TRUE(out.truncated || out.frames.size() < clean.expected.size());
    }
    reported += !out.errors.empty() || out.truncated;
    // Every GOP that starts after the damaged byte's GOP decodes completely, in order.
    std::vector<uint32_t> got;
    for (const auto& frame : out.frames) got.push_back(frame.first);
    for (size_t g = 0; g < clean.gop_starts.size(); ++g) {
      const bool before = g + 1 < clean.gop_starts.size() && clean.gop_starts[g + 1] <= at;
      const bool after = clean.gop_starts[g] > at;
      if (damage == Damage::kTruncate && after) continue;  // cut off
      if (!before && !after) continue;                     // the damaged GOP
      for (uint32_t index : clean.gop_frames[g]) {
        EXPECT_NE(std::find(got.begin(), got.end(), index), got.end())
            << "GOP " << g << " frame " << index << " missing";
      }
      resumed_gops += after;
    }
  }
  EXPECT_GT(reported, 900);
  // Coverage guard: decoding resumes only at a random-access GOP, and most streams have one
  // (the encoded ones keep their static layer across GOPs), so about a tenth of the trials
  // damage a byte before a later random-access GOP (measured: 103).
  EXPECT_GT(resumed_gops, 80);
}

std::map<uint32_t, std::string> CleanHashes(const std::vector<Packet>& packets, uint32_t layers) {
  M4dSettings settings = DefaultSettings();
  settings.layers = layers;
  const DecodeResult result = DecodeWith(settings, packets);
  std::map<uint32_t, std::string> hashes;
  for (size_t i = 0; i < result.hashes.size(); ++i)
    hashes[result.frame_indices[i]] = result.hashes[i];
  return hashes;
}

// The bytes of a packet a flip may hit: header fields by offset, then the payload's first,
// middle and last byte.
struct ByteClass {
  const char* name;
  size_t offset;  // into the header, or a share of the payload
  bool payload;
};
constexpr ByteClass kClasses[] = {
    {"sync", 1, false},          {"type", 4, false},        {"flags", 5, false},
    {"reserved", 6, false},      {"frame_index", 8, false}, {"payload_size", 13, false},
    {"payload_crc", 16, false},  {"header_crc", 21, false}, {"payload first", 0, true},
    {"payload middle", 1, true}, {"payload last", 2, true}};

size_t FlipOffset(const ByteClass& c, size_t packet_start, size_t packet_size) {
  if (!c.payload) return packet_start + c.offset;
  const size_t payload = packet_size - 24;
  const size_t at = c.offset == 0 ? 0 : c.offset == 1 ? payload / 2 : payload - 1;
  return packet_start + 24 + at;
}

TEST(DamageResilience, APayloadFlipInEveryPacketTypeCostsNoFrame) {
  TestStreamShape shape;
  shape.gops = 3;
  shape.frames_per_gop = 3;
  shape.static_count = 300;
  shape.dynamic_count = 120;
  shape.dependent_gops = true;  // the static layer is sent once, as the encoder does
  shape.static_change_step = 10;
  shape.appearance = true;
  const TestStream stream = MakeTestStream(shape);
  std::vector<uint8_t> bytes;
  std::map<uint32_t, size_t> first_of_type;  // packet type -> byte offset of its first packet
  for (const Packet& p : stream.packets) {
    first_of_type.emplace(p[4], bytes.size());
    bytes.insert(bytes.end(), p.begin(), p.end());
  }
  ASSERT_EQ(first_of_type.size(), 8u);
  CleanStream clean = LoadBytes("test stream", bytes);
  clean.expected = CleanHashes(stream.packets, M4D_LAYER_ALL);
  clean.static_only = CleanHashes(stream.packets, M4D_LAYER_STATIC);
  clean.dynamic_only = CleanHashes(stream.packets, M4D_LAYER_DYNAMIC);
  const size_t held = clean.expected.size();
  ASSERT_EQ(held, 9u);

  std::printf("frames output of %zu after one flipped byte (concealed in brackets)\n%-18s", held,
              "packet");
  for (const ByteClass& c : kClasses) std::printf(" %8.8s", c.name);
  std::printf("\n");
  for (const auto& [type, start] : first_of_type) {
    M4dPacketInfo info;
    ASSERT_EQ(m4d_parse_packet_header(&bytes[start], bytes.size() - start, &info), M4D_OK);
    std::printf("%-18u", type);
    for (const ByteClass& c : kClasses) {
      std::vector<uint8_t> damaged = bytes;
      damaged[FlipOffset(c, start, info.packet_size)] ^= 0x24;
      const PlayResult out = PlayBytes(DefaultSettings(), damaged);
      SCOPED_TRACE(std::string("packet type ") + std::to_string(type) + ", " + c.name);
      EXPECT_FALSE(out.errors.empty());
      size_t concealed = 0;
      for (size_t i = 0; i < out.frames.size(); ++i) {
        const auto& [index, hash] = out.frames[i];
        ASSERT_EQ(clean.expected.count(index), 1u);
        EXPECT_EQ(hash, ExpectedHash(clean, index, out.concealed[i])) << "frame " << index;
        concealed += out.concealed[i] != 0;
      }
      std::printf(" %4zu [%zu]", out.frames.size(), concealed);
      // A damaged payload of a layer loses that layer, not a frame (spec 6.8).
      if (c.payload && type != M4D_PACKET_SEQUENCE_HEADER) {
        EXPECT_EQ(out.frames.size(), held);
        EXPECT_GT(concealed, 0u);
      }
    }
    std::printf("\n");
  }
}

}  // namespace
}  // namespace testing
}  // namespace m4d
