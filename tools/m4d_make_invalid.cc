// m4d_make_invalid: writes the invalid conformance streams. Each starts from one small valid
// stream (2 GOPs of 3 frames from the reference stream writer) and breaks one rule of the
// specification: truncations, damaged headers and CRCs, out-of-range fields, inconsistent
// counts, oversized declarations, damaged Draco and entropy payloads. Edits that must reach a
// payload parser recompute the CRCs. Writes DIR/<name>.m4d and DIR/EXPECTED, one line per
// stream: "<name> <error> <what is wrong>", where <error> is the M4D_ERR_* code a decoder must
// report first, TRUNCATED when the stream ends inside a packet or a frame, or NONE where a
// decoder passes the rule broken without error (a stream joined inside a GOP). With
// --valid-dir it writes instead the valid streams at the edges of the rules (edit_*: frame
// numbers that wrap, a non-minimal varuint, a rANS state that starts below L).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/entropy/symbol_decoding.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/draco_types.h>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "encoder/src/layers/adaptive_attributes_writer.h"
#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "m4d/m4d.h"
#include "sdk/src/bitstream/packet_header.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/crc32.h"
#include "tools/usage_exit.h"

namespace {

using Packet = std::vector<uint8_t>;
using Stream = std::vector<Packet>;  // packets in order

// The base: packets 0..7 are GOP 0 (SEQUENCE_HEADER, KEYFRAME_STATIC, KEYFRAME_DYNAMIC,
// MLP_WEIGHTS, then MOTION_GRID and COMPENSATION of frames 1 and 2), 8..15 GOP 1.
enum : size_t { kSeq = 0, kStatic = 1, kDynamic = 2, kMlp = 3, kMotion = 4, kComp = 5 };

// Its sets keep every attribute in Draco, whose payload many cases damage (version 0.8's
// adaptive attributes have cases of their own, AdaptiveCodebookSet).
bool MakeBase(int version_minor, Stream* out, int opacity_bits = 8, int sh_rest_bits = 5) {
  m4d::StreamWriterOptions options;
  options.sequence.version_minor = version_minor;
  options.quantization.opacity_bits = opacity_bits;
  options.quantization.sh_rest_bits = sh_rest_bits;
  options.quantization.attribute_coding = m4d::AttributeCoding::kDraco;
  options.compensation_quantization.attribute_coding = m4d::AttributeCoding::kDraco;
  options.sequence.sh_degree = 1;
  options.sequence.grid.resolution[0] = 8;
  options.sequence.grid.resolution[1] = 12;
  options.sequence.grid.resolution[2] = 20;
  options.sequence.mlp.hidden_width = 16;
  m4d::StreamWriter writer(options);
  const float center[3] = {0, 0, 0}, fg[3] = {0.1f, 0.2f, -0.1f};
  for (int g = 0; g < 2; ++g) {
    const uint64_t seed = 900 + g;
    m4d::DecodedFrame recon;
    m4d::Status s = writer.WriteKeyframe(
        m4d::SyntheticGaussianSet(150, 1, seed, center, 2.0f),
        m4d::SyntheticGaussianSet(80, 1, seed + 1, fg, 0.4f),
        m4d::SyntheticMlp(options.sequence.grid.feature_count(), options.sequence.mlp, seed),
        &recon);
    for (int f = 1; f < 3 && s.ok(); ++f) {
      s = writer.WriteMotion(
          m4d::SyntheticMotionGrid(options.sequence.grid, seed * 7 + f, -0.6f, 0.6f, 0.2f));
      std::vector<uint8_t> removed(writer.moved_dynamic_set().size(), 0);
      for (size_t i = f; i < removed.size(); i += 17) removed[i] = 1;
      if (s.ok()) {
        s = writer.WriteCompensation(
            removed, m4d::SyntheticGaussianSet(6 + f, 1, seed * 13 + f, fg, 0.4f), &recon);
      }
    }
    if (!s.ok()) {
      std::fprintf(stderr, "m4d_make_invalid: base stream: %s\n", s.message().c_str());
      return false;
    }
  }
  const std::vector<uint8_t>& bytes = writer.bytes();
  M4dPacketInfo info;
  for (size_t pos = 0; pos < bytes.size(); pos += info.packet_size) {
    if (m4d_parse_packet_header(&bytes[pos], bytes.size() - pos, &info) != M4D_OK) return false;
    out->emplace_back(bytes.begin() + pos, bytes.begin() + pos + info.packet_size);
  }
  return out->size() == 16;
}

void FixCrcs(Packet* p) {
  const uint32_t payload_crc = m4d::Crc32(p->data() + 24, p->size() - 24);
  const uint32_t size = static_cast<uint32_t>(p->size() - 24);
  for (int i = 0; i < 4; ++i) {
    (*p)[12 + i] = static_cast<uint8_t>(size >> (8 * i));
    (*p)[16 + i] = static_cast<uint8_t>(payload_crc >> (8 * i));
  }
  const uint32_t header_crc = m4d::Crc32(p->data(), 20);
  for (int i = 0; i < 4; ++i) (*p)[20 + i] = static_cast<uint8_t>(header_crc >> (8 * i));
}

uint32_t ByteReaderU32(const Packet& p, size_t at) {
  return uint32_t(p[at]) | uint32_t(p[at + 1]) << 8 | uint32_t(p[at + 2]) << 16 |
         uint32_t(p[at + 3]) << 24;
}

std::vector<uint8_t> Varuint(uint32_t v) {
  std::vector<uint8_t> out;
  do {
    out.push_back(static_cast<uint8_t>((v & 0x7f) | (v >= 0x80 ? 0x80 : 0)));
    v >>= 7;
  } while (v);
  return out;
}

size_t VaruintLength(const Packet& p, size_t at) {
  size_t n = 1;
  while (p[at + n - 1] & 0x80) ++n;
  return n;
}

uint32_t ReadVaruint(const Packet& p, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < VaruintLength(p, at); ++i) v |= uint32_t(p[at + i] & 0x7f) << (7 * i);
  return v;
}

// Replaces the varuint at payload offset `at` of packet p by `value` (CRCs fixed).
void SetVaruint(Packet* p, size_t at, uint32_t value) {
  at += 24;
  const std::vector<uint8_t> bytes = Varuint(value);
  p->erase(p->begin() + at, p->begin() + at + VaruintLength(*p, at));
  p->insert(p->begin() + at, bytes.begin(), bytes.end());
  FixCrcs(p);
}

// Payload offset of the position group's codebook_size in a set packet (version 0.6): after
// the count, bits, per_component and its (min, step) pairs.
size_t PositionCodebookOffset(const Packet& p) {
  const size_t count_length = VaruintLength(p, 24);
  const bool per_component = p[24 + count_length + 1] != 0;
  return count_length + 2 + 8 * (per_component ? 3 : 1);
}

size_t Find(const Packet& p, const char* text) {
  const size_t n = std::strlen(text);
  for (size_t i = 24; i + n <= p.size(); ++i) {
    if (std::memcmp(&p[i], text, n) == 0) return i;
  }
  return p.size();
}

// Offset in a set packet of the byte before draco_size, the varuint before the Draco magic:
// attribute_coding (version 0.8).
size_t AttributeCodingOffset(const Packet& p) {
  size_t i = Find(p, "DRACO") - 1;  // draco_size's last byte
  while (p[i - 1] & 0x80) --i;
  return i - 1;
}

// Payload offset of what follows the symbol_block at payload offset `at` (spec 5.1).
size_t SkipSymbolBlock(const Packet& p, size_t at) {
  const uint32_t n = ReadVaruint(p, 24 + at);
  at += VaruintLength(p, 24 + at);
  at += VaruintLength(p, 24 + at);  // min_value
  if (n == 1) return at;
  for (uint32_t i = 0; i < n;) {
    const uint32_t f = ReadVaruint(p, 24 + at);
    at += VaruintLength(p, 24 + at);
    ++i;
    if (f == 0) {
      i += ReadVaruint(p, 24 + at);
      at += VaruintLength(p, 24 + at);
    }
  }
  const uint32_t payload_size = ReadVaruint(p, 24 + at);
  return at + VaruintLength(p, 24 + at) + payload_size;
}

// The last version whose MOTION_GRID has the brick syntax (spec 4.4); the cases that damage it
// edit a stream of that version.
constexpr int kBrickSyntaxMinor = 9;

// Payload offsets in a MOTION_GRID (spec 4.4) of level 0's brick_flags and values blocks. The
// base stream's level 0 is one brick of 8^3 voxels, flagged.
constexpr size_t kBrickFlagsOffset = 28;  // after box_min, box_scale and level 0's step
size_t GridValuesOffset(const Packet& p) { return SkipSymbolBlock(p, kBrickFlagsOffset); }

void SetU32(Packet* p, size_t at, uint32_t value) {
  for (int i = 0; i < 4; ++i) (*p)[at + i] = static_cast<uint8_t>(value >> (8 * i));
}

// Every frame_index from packet `first` on moved by `delta` (mod 2^32), CRCs fixed.
void ShiftFrameIndices(Stream* s, size_t first, uint32_t delta) {
  for (size_t i = first; i < s->size(); ++i) {
    Packet& p = (*s)[i];
    SetU32(&p, 8, ByteReaderU32(p, 8) + delta);
    FixCrcs(&p);
  }
}

// A gaussian_set() (spec 5.4, version 0.6 and later) of `count` equal Gaussians of SH degree 0:
// every group constant (bits 0), its Draco payload the 16 bytes of a point cloud without
// attributes. Position (100, 100, 100), outside every motion grid box of the base stream.
std::vector<uint8_t> ConstantSet(uint32_t count) {
  std::vector<uint8_t> payload;
  m4d::ByteWriter w(&payload);
  w.WriteVarUint(count);
  const float mins[5] = {100.0f, -4.0f, 0.0f, 1.0f, 0.5f};  // position .. sh_dc
  for (float min : mins) {
    w.WriteU8(0);  // bits
    w.WriteU8(0);  // per_component
    w.WriteF32(min);
    w.WriteF32(0.0f);   // step
    w.WriteVarUint(0);  // codebook_size
  }
  w.WriteU8(0);  // attribute_coding (0.8): Draco
  const uint8_t header[11] = {'D', 'R', 'A', 'C', 'O', 2, 3, 0, 0, 0, 0};
  w.WriteVarUint(16);
  w.WriteBytes(header, sizeof(header));
  w.WriteU32(count);
  w.WriteU8(0);  // no attribute decoder
  return payload;
}

Packet MakePacket(uint8_t type, uint32_t frame_index, bool end_of_frame,
                  const std::vector<uint8_t>& payload) {
  Packet packet;
  m4d::AppendPacket(type, frame_index, end_of_frame, payload.data(), payload.size(), &packet);
  return packet;
}

// A KEYFRAME_STATIC set of two Gaussians of SH degree 1 at (100, 100, 100), every group
// constant but the log scales: a codebook of 3 entries at 1 bit, the indices `indices` (2 bits
// each, spec 5.7) coded as adaptive_attributes() with attribute_coding `coding`, its payload
// changed by `edit` before it is written.
Packet AdaptiveCodebookSet(std::vector<uint32_t> indices, uint8_t coding,
                           const std::function<void(std::vector<uint8_t>*)>& edit) {
  std::vector<uint8_t> payload;
  m4d::ByteWriter w(&payload);
  w.WriteVarUint(static_cast<uint32_t>(indices.size()));
  const float mins[6] = {100.0f, -4.0f, 0.0f, 1.0f, 0.5f, 0.0f};  // position .. sh_rest
  for (int g = 0; g < 6; ++g) {
    w.WriteU8(g == 1 ? 1 : 0);  // bits
    w.WriteU8(0);               // per_component
    w.WriteF32(mins[g]);
    w.WriteF32(g == 1 ? 1.0f : 0.0f);  // step
    w.WriteVarUint(g == 1 ? 3 : 0);    // codebook_size
    if (g == 1) {
      const int32_t entries[9] = {0, 0, 0, 1, 0, 1, 1, 1, 0};
      m4d::WriteSymbolBlock(entries, 9, m4d::RansLayout::kInterleaved, &w);
    }
  }
  w.WriteU8(coding);
  m4d::AdaptiveField field;
  field.components = 1;
  field.width = 2;
  field.limit = 4;
  field.q = indices.data();
  std::vector<uint8_t> adaptive =
      m4d::EncodeAdaptiveAttributes(&field, 1, static_cast<uint32_t>(indices.size()));
  edit(&adaptive);
  w.WriteVarUint(static_cast<uint32_t>(adaptive.size()));
  w.WriteBytes(adaptive);
  return MakePacket(M4D_PACKET_KEYFRAME_STATIC, 0, false, payload);
}

// Replaces the static keyframe of GOP 0 by AdaptiveCodebookSet(indices, coding, edit).
std::function<void(Stream*, std::vector<uint8_t>*)> SetAdaptiveStatic(
    std::vector<uint32_t> indices, uint8_t coding = 1,
    std::function<void(std::vector<uint8_t>*)> edit = [](std::vector<uint8_t>*) {}) {
  return [=](Stream* s, std::vector<uint8_t>*) {
    (*s)[kStatic] = AdaptiveCodebookSet(indices, coding, edit);
  };
}

// A MOTION_GRID of the base's three levels whose box holds no finite position: no voxel is
// active (spec 4.4, 0.10), so it fits any dynamic set.
std::vector<uint8_t> EmptyMotionGrid() {
  std::vector<uint8_t> grid;
  m4d::ByteWriter w(&grid);
  for (int a = 0; a < 3; ++a) w.WriteF32(std::numeric_limits<float>::max());
  for (int a = 0; a < 3; ++a) w.WriteF32(1.0f);
  for (int l = 0; l < 3; ++l) {
    w.WriteF32(1.0f / 64);
    w.WriteVarUint(1);  // a one-symbol block of 0: no value
    w.WriteVarSint(0);
  }
  return grid;
}

// GOP 0 replaced by a foreground-only GOP of SH degree 0 whose dynamic set holds
// MAX_GAUSSIANS_PER_SET Gaussians and whose frame 1 adds one more (spec 9, E33).
void DynamicSetAboveLimit(Stream* s, std::vector<uint8_t>*) {
  Packet sequence = (*s)[kSeq];
  sequence[24 + 3] = 0;  // sh_degree
  FixCrcs(&sequence);
  std::vector<uint8_t> compensation;
  m4d::ByteWriter w(&compensation);
  w.WriteVarUint(0);  // num_removed
  w.WriteBytes(ConstantSet(1));
  Stream gop = {sequence, MakePacket(M4D_PACKET_KEYFRAME_DYNAMIC, 0, false, ConstantSet(1u << 22)),
                (*s)[kMlp], MakePacket(M4D_PACKET_MOTION_GRID, 1, false, EmptyMotionGrid()),
                MakePacket(M4D_PACKET_COMPENSATION, 1, true, compensation)};
  s->erase(s->begin(), s->begin() + 8);
  s->insert(s->begin(), gop.begin(), gop.end());
}

// Payload offset of the payload_size of the last symbol block of a MOTION_GRID (the last
// level's values; spec 4.4) with three levels, as the base stream's.
size_t LastGridBlockPayloadSizeOffset(const Packet& p) {
  size_t at = 24, values = 0;  // after box_min, box_scale
  for (int l = 0; l < 3; ++l) {
    values = SkipSymbolBlock(p, at + 4);  // after step and brick_flags
    at = SkipSymbolBlock(p, values);
  }
  const uint32_t n = ReadVaruint(p, 24 + values);
  at = values + VaruintLength(p, 24 + values);
  at += VaruintLength(p, 24 + at);  // min_value
  for (uint32_t i = 0; i < n;) {
    const uint32_t f = ReadVaruint(p, 24 + at);
    at += VaruintLength(p, 24 + at);
    ++i;
    if (f == 0) {
      i += ReadVaruint(p, 24 + at);
      at += VaruintLength(p, 24 + at);
    }
  }
  return at;
}

// A KEYFRAME_STATIC set (SH degree 1) of 64 Gaussians at (100, 100, 100) whose log scales,
// opacities and SH DC are coded as adaptive_attributes() at 16, 13 and 20 bits: values wider
// than the bit tree's 8 bits end in bypass bits (spec 5.7).
Packet AdaptiveWideSet() {
  constexpr uint32_t kCount = 64;
  std::vector<uint8_t> payload;
  m4d::ByteWriter w(&payload);
  w.WriteVarUint(kCount);
  const float mins[6] = {100.0f, -6.0f, 0.0f, -4.0f, -1.0f, 0.0f};  // position .. sh_rest
  const int bits[6] = {0, 16, 0, 13, 20, 0};
  for (int g = 0; g < 6; ++g) {
    w.WriteU8(static_cast<uint8_t>(bits[g]));
    w.WriteU8(0);  // per_component
    w.WriteF32(mins[g]);
    w.WriteF32(bits[g] > 0 ? 1.0f / float(1 << (bits[g] - 2)) : 0.0f);  // step
    w.WriteVarUint(0);                                                  // codebook_size
  }
  w.WriteU8(1);  // attribute_coding: adaptive; no Draco attribute is left
  std::vector<uint32_t> q[3];
  m4d::AdaptiveField fields[3];
  const int field_bits[3] = {16, 13, 20}, components[3] = {3, 1, 3};
  uint32_t x = 12345;
  for (int f = 0; f < 3; ++f) {
    for (uint32_t i = 0; i < kCount * components[f]; ++i) {
      x = x * 1664525u + 1013904223u;
      // Spread over the whole width, so that bypass bits and contexts vary.
      q[f].push_back((((i * 997u) << (field_bits[f] - 10)) + (x >> 22)) &
                     ((1u << field_bits[f]) - 1));
    }
    fields[f].components = components[f];
    fields[f].width = field_bits[f];
    // Log scales on their own previous component, SH DC on the previous channel (spec 5.7).
    fields[f].context = f == 0   ? m4d::AdaptiveContext::kNeighbourAndOwn
                        : f == 2 ? m4d::AdaptiveContext::kPreviousChannel
                                 : m4d::AdaptiveContext::kNeighbour;
    fields[f].limit = 1u << field_bits[f];
    fields[f].q = q[f].data();
  }
  const std::vector<uint8_t> adaptive = m4d::EncodeAdaptiveAttributes(fields, 3, kCount);
  w.WriteVarUint(static_cast<uint32_t>(adaptive.size()));
  w.WriteBytes(adaptive);
  return MakePacket(M4D_PACKET_KEYFRAME_STATIC, 0, false, payload);
}

// GOP 0 replaced by one of SH degree 0 whose static set holds MAX_GAUSSIANS_PER_SET Gaussians
// and whose frame 1, a dependent keyframe, adds one more with its STATIC_UPDATE (spec 9, E33).
void StaticSetAboveLimit(Stream* s, std::vector<uint8_t>*) {
  Packet sequence = (*s)[kSeq];
  sequence[24 + 3] = 0;  // sh_degree
  FixCrcs(&sequence);
  std::vector<uint8_t> update;
  m4d::ByteWriter w(&update);
  w.WriteVarUint(0);  // num_removed
  w.WriteBytes(ConstantSet(1));
  Packet mlp = (*s)[kMlp];
  SetU32(&mlp, 8, 1);
  FixCrcs(&mlp);
  Stream gop = {sequence,
                MakePacket(M4D_PACKET_KEYFRAME_STATIC, 0, false, ConstantSet(1u << 22)),
                MakePacket(M4D_PACKET_KEYFRAME_DYNAMIC, 0, false, ConstantSet(1)),
                (*s)[kMlp],
                MakePacket(M4D_PACKET_STATIC_UPDATE, 1, false, update),
                MakePacket(M4D_PACKET_KEYFRAME_DYNAMIC, 1, false, ConstantSet(1)),
                mlp};
  s->erase(s->begin(), s->begin() + 8);
  s->insert(s->begin(), gop.begin(), gop.end());
}

// Payload offset in a set packet of the base stream (SH degree 1, no codebooks) of group g's
// bits (spec 5.4); g = 6 gives the octree flag's.
size_t GroupOffset(const Packet& p, int g) {
  static const int kComponents[6] = {3, 3, 3, 1, 3, 9};
  size_t at = VaruintLength(p, 24);
  for (int k = 0; k < g; ++k) {
    const bool per_component = p[24 + at + 1] != 0;
    at += 2 + 8 * (per_component ? kComponents[k] : 1);
    at += VaruintLength(p, 24 + at);  // codebook_size 0
  }
  return at;
}

// A static keyframe set's opacity written at 9 bits (Draco UINT16 values up to 511, prediction
// none), then declared 8 bits with a UINT8 attribute: spec 5.5 keeps each value's low 8 bits.
void DracoValuesTruncated(Stream* s, std::vector<uint8_t>*) {
  s->clear();
  if (!MakeBase(M4D_BITSTREAM_VERSION_MINOR, s, 9)) return;
  Packet& p = (*s)[kStatic];
  p[24 + GroupOffset(p, 3)] = 8;
  // Attributes: positions (unless an octree holds them), log scales, rotations, their index.
  const size_t opacity = p[24 + GroupOffset(p, 6)] == 1 ? 3 : 4;
  p[Find(p, "DRACO") + 17 + 5 * opacity + 1] = draco::DT_UINT8;
  FixCrcs(&p);
}

// One attribute of a set packet's Draco payload (spec 5.5), as packet offsets.
struct DracoAttribute {
  size_t symbols = 0, symbols_end = 0;  // draco_symbols()
  size_t tag_bits = 0;                  // tagged: where tag_bits starts
  bool tagged = false, delta = false;
};

// Skips a Draco rANS frequency table of `n` entries at packet offset `at`.
size_t SkipDracoFrequencies(const Packet& p, size_t at, uint32_t n) {
  for (uint32_t i = 0; i < n; ++i) {
    const uint8_t t = p[at++];
    if ((t & 3) == 3) {
      i += t >> 2;
    } else {
      at += t & 3;
    }
  }
  return at;
}

// The attributes of the Draco payload of set packet p (ending at *end), or none where the
// payload does not walk (Draco decodes the tagged values to find where they end).
std::vector<DracoAttribute> DracoAttributes(const Packet& p, size_t* end) {
  const size_t start = Find(p, "DRACO");
  size_t size_at = start - 1;
  while (p[size_at - 1] & 0x80) --size_at;
  *end = start + ReadVaruint(p, size_at);
  const uint32_t count = ByteReaderU32(p, start + 11);
  const size_t num_attributes = p[start + 16];
  size_t at = start + 17 + 6 * num_attributes;  // descriptors, decoder types
  std::vector<DracoAttribute> attributes(num_attributes);
  std::vector<uint32_t> values;
  for (size_t j = 0; j < num_attributes; ++j) {
    DracoAttribute& a = attributes[j];
    const int components = p[start + 17 + 5 * j + 2];
    a.delta = p[at++] == draco::PREDICTION_DIFFERENCE;
    if (a.delta) ++at;  // transform
    ++at;               // compressed
    a.symbols = at;
    a.tagged = p[at] == draco::SYMBOL_CODING_TAGGED;
    if (a.tagged) {
      const uint32_t num_tags = ReadVaruint(p, at + 1);
      at = SkipDracoFrequencies(p, at + 1 + VaruintLength(p, at + 1), num_tags);
      a.tag_bits = at + VaruintLength(p, at) + ReadVaruint(p, at);
      draco::DecoderBuffer buffer;
      buffer.Init(reinterpret_cast<const char*>(&p[a.symbols]), *end - a.symbols,
                  DRACO_BITSTREAM_VERSION(2, 3));
      values.resize(static_cast<size_t>(count) * components);
      if (!draco::DecodeSymbols(count * components, components, &buffer, values.data())) return {};
      at = a.symbols + buffer.decoded_size();
    } else {
      const uint32_t num_symbols = ReadVaruint(p, at + 2);
      at = SkipDracoFrequencies(p, at + 2 + VaruintLength(p, at + 2), num_symbols);
      at += VaruintLength(p, at) + ReadVaruint(p, at);
    }
    a.symbols_end = at;
    if (a.delta) at += 8;  // wrap_min, wrap_max
  }
  if (at != *end) return {};
  return attributes;
}

// A static keyframe set whose SH rest (the Draco payload's last attribute) is written at 16
// bits, which Draco codes with the tagged scheme and no prediction (the writer predicts groups
// over 16 bits, whose wrap bounds would follow the tag bits). Its payload loses its last 2
// bytes, the last tag bits, which read as 0 (spec 5.5). And the first attribute with difference
// prediction (SH DC) is recoded with tags all 0 (one tag symbol of frequency 4096, a 1-byte rANS
// payload of state L): no tag bit is read, wrap_min follows the tags' payload, every value is
// wrap_min.
void DracoTagBitsCut(Stream* s, std::vector<uint8_t>*) {
  s->clear();
  Stream base;
  if (!MakeBase(M4D_BITSTREAM_VERSION_MINOR, &base, 8, 16)) return;
  Packet p = base[kStatic];
  size_t end;
  const std::vector<DracoAttribute> attributes = DracoAttributes(p, &end);
  if (attributes.size() < 2) return;
  const DracoAttribute& last = attributes.back();
  constexpr size_t kCut = 2;
  if (!last.tagged || last.delta || last.tag_bits + kCut >= end) return;
  p.erase(p.begin() + end - kCut, p.begin() + end);
  auto zero = std::find_if(attributes.begin(), attributes.end() - 1,
                           [](const DracoAttribute& a) { return a.delta; });
  if (zero == attributes.end() - 1) return;
  const uint8_t all_zero[] = {draco::SYMBOL_CODING_TAGGED, 1, 0x01, 0x40, 1, 0x00};
  p.erase(p.begin() + zero->symbols, p.begin() + zero->symbols_end);
  p.insert(p.begin() + zero->symbols, all_zero, all_zero + sizeof(all_zero));
  const size_t draco_size =
      end - kCut - (zero->symbols_end - zero->symbols) + sizeof(all_zero) - Find(p, "DRACO");
  SetVaruint(&p, AttributeCodingOffset(p) + 1 - 24, static_cast<uint32_t>(draco_size));
  base[kStatic] = p;
  *s = base;
}

// An APPEARANCE packet of frame 1 (spec 4.7) for its 80 dynamic Gaussians, or `values` of them.
Packet AppearancePacket(float step, uint32_t values = 3 * 80) {
  std::vector<int32_t> q(values);
  for (size_t i = 0; i < q.size(); ++i) q[i] = static_cast<int32_t>(i % 7) - 3;
  std::vector<uint8_t> payload;
  m4d::ByteWriter writer(&payload);
  writer.WriteF32(step);
  if (!m4d::WriteSymbolBlock(q.data(), q.size(), m4d::RansLayout::kInterleaved, &writer).ok())
    return {};
  Packet packet;
  m4d::AppendPacket(M4D_PACKET_APPEARANCE, 1, false, payload.data(), payload.size(), &packet);
  return packet;
}

struct Case {
  const char* name;
  const char* error;
  const char* what;
  std::function<void(Stream*, std::vector<uint8_t>* tail)> edit;  // tail: bytes appended
  // The base stream's version. A stream that declares 0.2 is edited from a 0.3 one, whose
  // symbol blocks are 0.2's (one rANS state).
  int base_minor = M4D_BITSTREAM_VERSION_MINOR;
};

// Payload offsets of SEQUENCE_HEADER (spec 4.1, three grid levels): 0 version_major,
// 1 version_minor, 2 profile, 3 sh_degree, 16 num_levels, 17.. channels, 20.. resolutions
// (u16), 26 mlp_hidden_layers, 27 mlp_hidden_width (u16), 29 up_axis (0.9).
std::function<void(Stream*, std::vector<uint8_t>*)> SetHeaderByte(size_t packet, size_t offset,
                                                                  uint8_t value, bool fix = true) {
  return [=](Stream* s, std::vector<uint8_t>*) {
    (*s)[packet][offset] = value;
    if (fix) FixCrcs(&(*s)[packet]);
  };
}

std::function<void(Stream*, std::vector<uint8_t>*)> SetPayloadByte(size_t packet, size_t offset,
                                                                   uint8_t value) {
  return SetHeaderByte(packet, 24 + offset, value);
}

std::vector<Case> Cases() {
  return {
      {"truncated_in_header", "TRUNCATED", "the stream ends 10 bytes into a packet header",
       [](Stream* s, std::vector<uint8_t>* tail) {
         *tail = Packet((*s)[kComp].begin(), (*s)[kComp].begin() + 10);
         s->resize(kComp);
       }},
      {"truncated_in_payload", "TRUNCATED", "the stream ends half way through a payload",
       [](Stream* s, std::vector<uint8_t>* tail) {
         const Packet& p = (*s)[8 + kDynamic];
         *tail = Packet(p.begin(), p.begin() + p.size() / 2);
         s->resize(8 + kDynamic);
       }},
      {"bad_sync_word", "M4D_ERR_BITSTREAM", "a packet header without its sync word",
       SetHeaderByte(kDynamic, 0, 'X')},
      {"bad_header_crc", "M4D_ERR_CHECKSUM", "a header field changed, header CRC not updated",
       SetHeaderByte(kDynamic, 8, 1, false)},
      {"bad_payload_crc", "M4D_ERR_CHECKSUM", "a payload byte changed, payload CRC not updated",
       [](Stream* s, std::vector<uint8_t>*) { (*s)[kDynamic][30] ^= 0x40; }},
      {"reserved_flag_bit", "M4D_ERR_BITSTREAM", "flags bit 1 set", SetHeaderByte(kMotion, 5, 2)},
      {"reserved_field", "M4D_ERR_BITSTREAM", "the reserved u16 of a header not 0",
       SetHeaderByte(kMotion, 7, 1)},
      {"unknown_packet_type", "M4D_ERR_UNSUPPORTED", "packet type 9", SetHeaderByte(kMotion, 4, 9)},
      {"payload_size_above_limit", "M4D_ERR_LIMIT",
       "a header declares a payload above MAX_PAYLOAD_SIZE (2^26)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         p[15] = 0x10;
         const uint32_t crc = m4d::Crc32(p.data(), 20);
         for (int i = 0; i < 4; ++i) p[20 + i] = static_cast<uint8_t>(crc >> (8 * i));
       }},
      {"unsupported_version", "M4D_ERR_UNSUPPORTED",
       "the bitstream minor version after the decoder's",
       SetPayloadByte(kSeq, 1, M4D_BITSTREAM_VERSION_MINOR + 1)},
      {"unsupported_profile", "M4D_ERR_UNSUPPORTED", "profile 1", SetPayloadByte(kSeq, 2, 1)},
      {"sh_degree_out_of_range", "M4D_ERR_BITSTREAM", "sh_degree 4", SetPayloadByte(kSeq, 3, 4)},
      {"grid_levels_out_of_range", "M4D_ERR_BITSTREAM", "num_levels 5 (MAX_GRID_LEVELS is 4)",
       SetPayloadByte(kSeq, 16, 5)},
      {"grid_values_above_limit", "M4D_ERR_LIMIT",
       "a 256^3 level of 2 channels: above MAX_GRID_VALUES",
       [](Stream* s, std::vector<uint8_t>*) {
         (*s)[kSeq][24 + 24] = 0;
         (*s)[kSeq][24 + 25] = 1;
         FixCrcs(&(*s)[kSeq]);
       }},
      {"mlp_width_out_of_range", "M4D_ERR_BITSTREAM", "mlp_hidden_width 257",
       [](Stream* s, std::vector<uint8_t>*) {
         (*s)[kSeq][24 + 27] = 1;
         (*s)[kSeq][24 + 28] = 1;
         FixCrcs(&(*s)[kSeq]);
       }},
      {"up_axis_out_of_range", "M4D_ERR_BITSTREAM", "up_axis 7 (0..6 are defined)",
       SetPayloadByte(kSeq, 29, 7)},
      {"keyframe_dynamic_missing", "M4D_ERR_BITSTREAM",
       "a keyframe's KEYFRAME_DYNAMIC missing (MLP_WEIGHTS follows KEYFRAME_STATIC)",
       [](Stream* s, std::vector<uint8_t>*) { s->erase(s->begin() + kDynamic); }},
      {"frame_index_gap", "M4D_ERR_BITSTREAM", "frame 2 numbered 3",
       [](Stream* s, std::vector<uint8_t>*) {
         (*s)[kMotion + 2][8] += 1;
         FixCrcs(&(*s)[kMotion + 2]);
       }},
      // Version 0.3's dependent keyframes: GOP 1 without its SEQUENCE_HEADER and
      // KEYFRAME_STATIC is one (valid); these break it.
      {"dependent_keyframe_in_v02_stream", "M4D_ERR_BITSTREAM",
       "a dependent keyframe in a stream that declares version 0.2",
       [](Stream* s, std::vector<uint8_t>*) {
         s->erase(s->begin() + 8, s->begin() + 8 + kDynamic);
         (*s)[kSeq][24 + 1] = 2;
         FixCrcs(&(*s)[kSeq]);
       },
       3},
      {"dependent_keyframe_index_gap", "M4D_ERR_BITSTREAM",
       "a dependent keyframe numbered one past the next frame",
       [](Stream* s, std::vector<uint8_t>*) {
         s->erase(s->begin() + 8, s->begin() + 8 + kDynamic);
         for (size_t p = 8; p < s->size(); ++p) {
           (*s)[p][8] += 1;
           FixCrcs(&(*s)[p]);
         }
       }},
      {"static_update_after_sequence_header", "M4D_ERR_BITSTREAM",
       "a STATIC_UPDATE in a random-access keyframe (KEYFRAME_STATIC's type changed to 7)",
       SetHeaderByte(kStatic, 4, M4D_PACKET_STATIC_UPDATE)},
      // Version 0.3's APPEARANCE (valid between a MOTION_GRID and its COMPENSATION).
      {"appearance_in_v02_stream", "M4D_ERR_BITSTREAM",
       "an APPEARANCE in a stream that declares version 0.2",
       [](Stream* s, std::vector<uint8_t>*) {
         s->insert(s->begin() + kComp, AppearancePacket(0.01f));
         (*s)[kSeq][24 + 1] = 2;
         FixCrcs(&(*s)[kSeq]);
       },
       3},
      {"appearance_step_zero", "M4D_ERR_BITSTREAM", "an APPEARANCE with step 0",
       [](Stream* s, std::vector<uint8_t>*) {
         s->insert(s->begin() + kComp, AppearancePacket(0.0f));
       }},
      {"appearance_values_short", "M4D_ERR_BITSTREAM",
       "an APPEARANCE with values for 79 of the 80 dynamic Gaussians",
       [](Stream* s, std::vector<uint8_t>*) {
         s->insert(s->begin() + kComp, AppearancePacket(0.01f, 3 * 79));
       }},
      {"appearance_after_compensation", "M4D_ERR_BITSTREAM",
       "an APPEARANCE after frame 1's COMPENSATION",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet p = AppearancePacket(0.01f);
         p[8] = 2;  // frame 2's MOTION_GRID follows: the packet ends frame 1's numbering
         FixCrcs(&p);
         s->insert(s->begin() + kComp + 1, p);
       }},
      {"compensation_without_motion_grid", "M4D_ERR_BITSTREAM", "frame 1's MOTION_GRID missing",
       [](Stream* s, std::vector<uint8_t>*) { s->erase(s->begin() + kMotion); }},
      {"missing_end_of_frame", "M4D_ERR_BITSTREAM",
       "the keyframe's last packet without end_of_frame", SetHeaderByte(kMlp, 5, 0)},
      {"trailing_payload_byte", "M4D_ERR_BITSTREAM", "a byte after a gaussian_set()",
       [](Stream* s, std::vector<uint8_t>*) {
         (*s)[kDynamic].push_back(0);
         FixCrcs(&(*s)[kDynamic]);
       }},
      {"gaussian_count_above_limit", "M4D_ERR_LIMIT",
       "a set declares 2^22 + 1 Gaussians (MAX_GAUSSIANS_PER_SET is 2^22)",
       [](Stream* s, std::vector<uint8_t>*) { SetVaruint(&(*s)[kDynamic], 0, (1u << 22) + 1); }},
      {"gaussian_count_inconsistent", "M4D_ERR_BITSTREAM",
       "a set's count one more than its Draco point count",
       [](Stream* s, std::vector<uint8_t>*) {
         SetVaruint(&(*s)[kDynamic], 0, ReadVaruint((*s)[kDynamic], 24) + 1);
       }},
      {"codebook_of_positions", "M4D_ERR_BITSTREAM",
       "a set's position group declares a codebook of 2 entries (only log scales, SH DC and "
       "higher SH may have one)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         SetVaruint(&p, PositionCodebookOffset(p), 2);
       }},
      {"codebook_size_above_limit", "M4D_ERR_LIMIT",
       "a set's codebook_size 4097 (MAX_CODEBOOK_SIZE is 4096)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         SetVaruint(&p, PositionCodebookOffset(p), 4097);
       }},
      {"octree_flag_not_binary", "M4D_ERR_BITSTREAM",
       "a set's octree flag 2 (since version 0.7: 0 or 1)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kStatic];
         p[24 + GroupOffset(p, 6)] = 2;
         FixCrcs(&p);
       }},
      {"attribute_coding_not_binary", "M4D_ERR_BITSTREAM",
       "a set's attribute_coding 2 (since version 0.8: 0 or 1)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kStatic];
         p[AttributeCodingOffset(p)] = 2;
         FixCrcs(&p);
       }},
      {"adaptive_index_above_codebook", "M4D_ERR_BITSTREAM",
       "adaptive attributes code index 3 of a codebook of 3 entries", SetAdaptiveStatic({1, 3})},
      {"adaptive_size_below_4", "M4D_ERR_BITSTREAM",
       "adaptive_attributes() of 3 bytes (the range decoder starts from 4)",
       SetAdaptiveStatic({1, 2}, 1, [](std::vector<uint8_t>* a) { a->resize(3); })},
      {"adaptive_payload_short", "M4D_ERR_BITSTREAM",
       "adaptive_attributes() without its last byte: decoding needs a byte past its end",
       SetAdaptiveStatic(std::vector<uint32_t>(300, 0), 1,
                         [](std::vector<uint8_t>* a) { a->pop_back(); })},
      {"adaptive_trailing_byte", "M4D_ERR_BITSTREAM",
       "adaptive_attributes() with a byte after what decoding reads",
       SetAdaptiveStatic({1, 2}, 1, [](std::vector<uint8_t>* a) { a->push_back(0); })},
      {"draco_bad_magic", "M4D_ERR_BITSTREAM", "the Draco header's magic damaged",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kStatic];
         p[Find(p, "DRACO") + 4] = 'X';
         FixCrcs(&p);
       }},
      {"draco_not_sequential", "M4D_ERR_BITSTREAM", "Draco method 1 (kd-tree) declared",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kStatic];
         p[Find(p, "DRACO") + 8] = 1;
         FixCrcs(&p);
       }},
      {"draco_payload_cut", "M4D_ERR_BITSTREAM",
       "the last 5 bytes of a Draco payload cut (draco_size now past the payload)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         p.resize(p.size() - 5);
         FixCrcs(&p);
       }},
      {"entropy_alphabet_above_limit", "M4D_ERR_LIMIT",
       "a symbol_block with alphabet_size 4097 (MAX_ALPHABET is 4096)",
       [](Stream* s, std::vector<uint8_t>*) { SetVaruint(&(*s)[kMotion], 28, 4097); }},
      {"entropy_alphabet_zero", "M4D_ERR_BITSTREAM", "a symbol_block with alphabet_size 0",
       [](Stream* s, std::vector<uint8_t>*) { SetVaruint(&(*s)[kMotion], 28, 0); }},
      {"entropy_rans_damaged", "M4D_ERR_BITSTREAM",
       "the last rANS payload byte of a MOTION_GRID changed (final state check)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         p.back() ^= 0x5a;
         FixCrcs(&p);
       }},
      // Stream structure (spec 9's structural cases).
      {"sequence_header_inside_frame", "M4D_ERR_BITSTREAM",
       "GOP 1's SEQUENCE_HEADER inside frame 2 (its COMPENSATION removed): frame 2 is dropped, "
       "GOP 1 decodes",
       [](Stream* s, std::vector<uint8_t>*) { s->erase(s->begin() + kComp + 2); }},
      {"stream_ends_inside_frame", "TRUNCATED",
       "the stream ends after frame 5's MOTION_GRID (its COMPENSATION missing)",
       [](Stream* s, std::vector<uint8_t>*) { s->pop_back(); }},
      {"starts_inside_gop", "NONE",
       "frame 1's MOTION_GRID and COMPENSATION before the first SEQUENCE_HEADER: skipped, no "
       "error",
       [](Stream* s, std::vector<uint8_t>*) {
         const Packet motion = (*s)[kMotion], compensation = (*s)[kComp];
         s->insert(s->begin(), {motion, compensation});
       }},
      // Fields out of their range (spec 9's BITSTREAM rows).
      {"frame_rate_zero", "M4D_ERR_BITSTREAM", "fps_num 0",
       [](Stream* s, std::vector<uint8_t>*) {
         SetU32(&(*s)[kSeq], 24 + 4, 0);
         FixCrcs(&(*s)[kSeq]);
       }},
      {"bits_above_24", "M4D_ERR_BITSTREAM", "a set's position bits 25",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         p[24 + VaruintLength(p, 24)] = 25;
         FixCrcs(&p);
       }},
      {"per_component_not_binary", "M4D_ERR_BITSTREAM", "a set's position per_component 2",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         p[24 + VaruintLength(p, 24) + 1] = 2;
         FixCrcs(&p);
       }},
      {"mlp_step_not_finite", "M4D_ERR_BITSTREAM", "layer 0's weight_step a NaN",
       [](Stream* s, std::vector<uint8_t>*) {
         SetU32(&(*s)[kMlp], 24, 0x7fc00000u);
         FixCrcs(&(*s)[kMlp]);
       }},
      {"box_scale_zero", "M4D_ERR_BITSTREAM", "a MOTION_GRID's box_scale x 0",
       [](Stream* s, std::vector<uint8_t>*) {
         SetU32(&(*s)[kMotion], 24 + 12, 0);
         FixCrcs(&(*s)[kMotion]);
       }},
      {"brick_flag_not_binary", "M4D_ERR_BITSTREAM", "level 0's brick flag 2",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         SetVaruint(&p, kBrickFlagsOffset + 1, 4);  // min_value 2 (zigzag): flags 2..
       },
       kBrickSyntaxMinor},
      {"grid_value_outside_int16", "M4D_ERR_BITSTREAM",
       "level 0's values from -40000 (below -32768)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         const size_t at = GridValuesOffset(p);
         SetVaruint(&p, at + VaruintLength(p, 24 + at), 79999);  // min_value -40000 (zigzag)
       },
       kBrickSyntaxMinor},
      {"active_grid_value_outside_int16", "M4D_ERR_BITSTREAM",
       "level 0's active-voxel values (0.10) from -40000 (below -32768)",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         const size_t at = kBrickFlagsOffset;                    // the values follow level 0's step
         SetVaruint(&p, at + VaruintLength(p, 24 + at), 79999);  // min_value -40000 (zigzag)
       }},
      {"alphabet_for_zero_values", "M4D_ERR_BITSTREAM",
       "level 0's brick flag 0 (no values) but its values block an alphabet of several symbols",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         SetVaruint(&p, kBrickFlagsOffset + 1, 0);  // min_value 0: the one brick not coded
       },
       kBrickSyntaxMinor},
      {"draco_version_not_2_3", "M4D_ERR_BITSTREAM", "the Draco header's minor version 2",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kStatic];
         p[Find(p, "DRACO") + 6] = 2;
         FixCrcs(&p);
       }},
      {"dynamic_set_above_limit", "M4D_ERR_LIMIT",
       "a COMPENSATION adds a Gaussian to a dynamic set of MAX_GAUSSIANS_PER_SET (2^22) constant "
       "ones",
       DynamicSetAboveLimit},
      {"removed_count_inconsistent", "M4D_ERR_BITSTREAM",
       "num_removed one more than the removal flags set",
       [](Stream* s, std::vector<uint8_t>*) {
         SetVaruint(&(*s)[kComp], 0, ReadVaruint((*s)[kComp], 24) + 1);
       }},
      // Branches of the reading process and of the check order (spec 3, 9's Order).
      {"payload_size_grown", "M4D_ERR_BITSTREAM",
       "GOP 0's KEYFRAME_DYNAMIC declares 30 bytes more (the next header's first 30, CRCs "
       "updated): its bytes left over are a layer error; reading resumes right after its header "
       "and finds MLP_WEIGHTS",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         std::vector<uint8_t> grown(p.begin() + 24, p.end());
         grown.insert(grown.end(), (*s)[kMlp].begin(), (*s)[kMlp].begin() + 30);
         SetU32(&p, 12, static_cast<uint32_t>(grown.size()));
         SetU32(&p, 16, m4d::Crc32(grown.data(), grown.size()));
         SetU32(&p, 20, m4d::Crc32(p.data(), 20));
       }},
      {"ends_inside_frame_unconfigured", "TRUNCATED",
       "only frame 1 and frame 2's MOTION_GRID: skipped with no configuration, the last header "
       "has no end_of_frame",
       [](Stream* s, std::vector<uint8_t>*) {
         *s = Stream(s->begin() + kMotion, s->begin() + kMotion + 3);
       }},
      {"sequence_header_end_of_frame_inside_frame", "M4D_ERR_BITSTREAM",
       "GOP 1's SEQUENCE_HEADER inside frame 2 with end_of_frame set: E8 before E12, so GOP 1 "
       "is not decoded",
       [](Stream* s, std::vector<uint8_t>*) {
         s->erase(s->begin() + kComp + 2);
         (*s)[kComp + 2][5] = 1;
         FixCrcs(&(*s)[kComp + 2]);
       }},
      {"faults_reserved_and_payload_size", "M4D_ERR_BITSTREAM",
       "frame 1's COMPENSATION header with reserved 1 and payload_size 2^26 + 1 (header CRC "
       "updated): E5 before E6",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kComp];
         p[6] = 1;
         SetU32(&p, 12, (1u << 26) + 1);
         SetU32(&p, 20, m4d::Crc32(p.data(), 20));
       }},
      {"unknown_type_before_sequence_header", "M4D_ERR_UNSUPPORTED",
       "a packet of type 9 before the first SEQUENCE_HEADER: E7 before the skip of E13",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet p = (*s)[kMotion];
         p[4] = 9;
         FixCrcs(&p);
         s->insert(s->begin(), p);
       }},
      {"faults_order_and_payload_crc", "M4D_ERR_BITSTREAM",
       "frame 1's MOTION_GRID missing and its COMPENSATION's payload CRC wrong: E9 before E14",
       [](Stream* s, std::vector<uint8_t>*) {
         s->erase(s->begin() + kMotion);
         (*s)[kMotion].back() ^= 0x21;
       }},
      {"faults_payload_crc_and_trailing_byte", "M4D_ERR_CHECKSUM",
       "a byte after a gaussian_set(), the payload CRC not updated: E14 before E15",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         const uint32_t crc = ByteReaderU32(p, 16);
         p.push_back(0);
         FixCrcs(&p);
         SetU32(&p, 16, crc);
         SetU32(&p, 20, m4d::Crc32(p.data(), 20));
       }},
      {"entropy_rans_payload_short", "M4D_ERR_BITSTREAM",
       "the last rANS payload of a MOTION_GRID one byte short: decoding needs a byte past it",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         const size_t at = LastGridBlockPayloadSizeOffset(p);
         const uint32_t size = ReadVaruint(p, 24 + at);
         p.pop_back();
         SetVaruint(&p, at, size - 1);
       },
       kBrickSyntaxMinor},
      {"static_set_above_limit", "M4D_ERR_LIMIT",
       "a STATIC_UPDATE adds a Gaussian to a static set of MAX_GAUSSIANS_PER_SET (2^22) constant "
       "ones",
       StaticSetAboveLimit},
      {"adaptive_wide_values", "TRUNCATED",
       "GOP 0's static set coded adaptively at 16, 13 and 20 bits (bypass bits past the tree's "
       "8; valid, every frame output), then the stream ends 5 bytes into a header",
       [](Stream* s, std::vector<uint8_t>* tail) {
         (*s)[kStatic] = AdaptiveWideSet();
         *tail = Packet((*s)[kSeq].begin(), (*s)[kSeq].begin() + 5);
       }},
  };
}

// Valid streams at the edges of the rules, edited from the same base (written with
// --valid-dir into the conformance streams): they decode without error.
std::vector<Case> ValidEdits() {
  return {
      {"edit_frame_index_wraps", "", "frames numbered 2^32 - 2, 2^32 - 1, 0, 1, 2, 3: valid",
       [](Stream* s, std::vector<uint8_t>*) { ShiftFrameIndices(s, 0, 0xfffffffeu); }},
      {"edit_varuint_not_minimal", "",
       "a dynamic set's count (80) coded in 3 bytes instead of 1: the same value",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kDynamic];
         const uint32_t count = ReadVaruint(p, 24);
         p.erase(p.begin() + 24, p.begin() + 24 + VaruintLength(p, 24));
         const uint8_t padded[3] = {static_cast<uint8_t>(0x80 | (count & 0x7f)),
                                    static_cast<uint8_t>(0x80 | (count >> 7)), 0};
         p.insert(p.begin() + 24, padded, padded + 3);
         FixCrcs(&p);
       }},
      {"edit_draco_values_truncated", "",
       "a static keyframe set's opacity coded at 9 bits, declared 8 bits with UINT8 Draco values: "
       "each value's low 8 bits count (spec 5.5)",
       DracoValuesTruncated},
      {"edit_draco_tag_bits_cut", "",
       "a static keyframe set's SH rest at 16 bits (Draco's tagged scheme, no prediction, its "
       "last attribute) with the last 2 bytes of the Draco payload cut: those tag bits read as "
       "0; and its SH DC recoded with every tag 0: no tag bit read (spec 5.5)",
       DracoTagBitsCut},
      {"edit_rans_initial_state_low", "",
       "level 0's brick flags (one 1) recoded with rANS from the initial state 2^15, below "
       "L_RANS: legal, the same frames",
       [](Stream* s, std::vector<uint8_t>*) {
         Packet& p = (*s)[kMotion];
         const size_t at = 24 + kBrickFlagsOffset, end = 24 + SkipSymbolBlock(p, kBrickFlagsOffset);
         // alphabet 2, min 0, frequencies {0 (then a run of 0 zeros), 32768}, a 5-byte payload:
         // symbol 1 keeps the state at 2^15, whose renormalisation reads one byte to reach L.
         const uint8_t block[] = {2, 0, 0, 0, 0x80, 0x80, 0x02, 5, 0x00, 0x80, 0x00, 0x00, 0x00};
         p.erase(p.begin() + at, p.begin() + end);
         p.insert(p.begin() + at, block, block + sizeof(block));
         FixCrcs(&p);
       },
       kBrickSyntaxMinor},
  };
}

bool WriteStream(const std::string& path, const Stream& stream, const std::vector<uint8_t>& tail) {
  std::ofstream file(path, std::ios::binary);
  for (const Packet& p : stream) file.write(reinterpret_cast<const char*>(p.data()), p.size());
  file.write(reinterpret_cast<const char*>(tail.data()), tail.size());
  return static_cast<bool>(file);
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir;
  CLI::App app{"Write the invalid conformance streams and their expected errors."};
  std::string valid_dir;
  // One of the two is required: nothing is written into a folder nobody named.
  CLI::Option* out = app.add_option("-o,--output-dir", dir, "where to write them");
  app.add_option("--valid-dir", valid_dir,
                 "write the valid edge-case streams (edit_*) there instead")
      ->excludes(out);
  app.require_option(1);
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  Stream base, base_v03, base_bricks;
  if (!MakeBase(M4D_BITSTREAM_VERSION_MINOR, &base) || !MakeBase(3, &base_v03) ||
      !MakeBase(kBrickSyntaxMinor, &base_bricks)) {
    return 1;
  }
  if (!valid_dir.empty()) {
    for (const Case& c : ValidEdits()) {
      Stream stream = c.base_minor == kBrickSyntaxMinor ? base_bricks : base;
      std::vector<uint8_t> tail;
      c.edit(&stream, &tail);
      if (stream.empty()) {
        std::fprintf(stderr, "m4d_make_invalid: %s: the base stream does not fit the edit\n",
                     c.name);
        return 1;
      }
      if (!WriteStream(valid_dir + "/" + c.name + ".m4d", stream, tail)) return 1;
      std::printf("%s: %s\n", c.name, c.what);
    }
    return 0;
  }
  std::ofstream expected(dir + "/EXPECTED");
  if (!expected) {
    std::fprintf(stderr, "m4d_make_invalid: cannot write %s/EXPECTED\n", dir.c_str());
    return 1;
  }
  expected << "# <stream> <first error a decoder reports> <what is wrong>\n";
  int written = 0;
  for (const Case& c : Cases()) {
    Stream stream = c.base_minor == 3                   ? base_v03
                    : c.base_minor == kBrickSyntaxMinor ? base_bricks
                                                        : base;
    std::vector<uint8_t> tail;
    c.edit(&stream, &tail);
    if (!WriteStream(dir + "/" + c.name + ".m4d", stream, tail)) return 1;
    expected << c.name << " " << c.error << " " << c.what << "\n";
    ++written;
  }
  std::printf("wrote %d invalid streams and EXPECTED to %s\n", written, dir.c_str());
  return 0;
}
