// The spec coverage table (bitstream-spec/coverage.md) is checked, not trusted: this test
// walks the syntax of every conformance stream (spec 4 and 5, independently of the SDK's
// parser) and records which syntax elements and value ranges it uses. Each row of the table
// names a feature and the streams that exercise it; every one of those streams must have the
// feature, and every feature the walk knows must have a row.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/compression/entropy/rans_symbol_decoder.h>
#include <draco/core/decoder_buffer.h>

#include "m4d/m4d.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/layers/octree_positions.h"

namespace {

const std::string kRoot = M4D_SOURCE_DIR;

// Reads the syntax of spec 1 from a payload; a read past the end fails the test.
class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint32_t U8() { return Need(1) ? data_[pos_++] : 0; }
  uint32_t U16() { return U8() | (U8() << 8); }
  uint32_t U32() { return U16() | (U16() << 16); }
  float F32() {
    const uint32_t bits = U32();
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
  }
  void Skip(size_t n) {
    if (Need(n)) pos_ += n;
  }
  uint32_t VarUint() {
    uint32_t v = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      const uint32_t b = U8();
      v |= (b & 127u) << shift;
      if (!(b & 128u)) {
        non_minimal_ = non_minimal_ || (shift > 0 && b == 0);  // a trailing zero group (spec 1)
        break;
      }
    }
    return v;
  }
  // A varuint of the payload had groups of zeros after its value.
  bool non_minimal() const { return non_minimal_; }
  int64_t VarSint() {
    const uint32_t z = VarUint();
    return static_cast<int64_t>(z >> 1) ^ -static_cast<int64_t>(z & 1);
  }
  bool done() const { return pos_ == size_; }
  size_t remaining() const { return size_ - pos_; }
  // The next byte, or null at the end.
  const uint8_t* Here() const { return pos_ < size_ ? data_ + pos_ : nullptr; }

 private:
  bool Need(size_t n) {
    EXPECT_LE(pos_ + n, size_) << "read past the payload";
    return pos_ + n <= size_;
  }
  const uint8_t* data_;
  size_t size_, pos_ = 0;
  bool non_minimal_ = false;
};

// Dequantization steps that are powers of two commute with rounding: a decoder that scales
// before instead of after a sum or product gets the same floats with them, other floats without.
bool PowerOfTwo(float step) {
  int exponent;
  return std::frexp(step, &exponent) == 0.5f;
}

struct Walk {
  std::set<std::string> features;
  int sh_degree = 0;
  int levels = 0;
  int mlp_layers = 0;
  bool static_in_gop = false;
  int inter_in_gop = 0;
  bool frame_complete = false;  // the previous packet ended a frame
  bool dependent = false;       // the current keyframe is a dependent one (0.3)
  int version_minor = 0;
  uint32_t dynamic_count = 0;  // |D|, which gives the count of APPEARANCE and removal blocks
  bool seen_packet = false;
  uint32_t last_frame_index = 0;

  void Add(const std::string& f) { features.insert(f); }

  // 5.1: returns (alphabet size, min). `count` is the block's value count where the walk knows
  // it (0 where it would take decoding another block).
  std::pair<uint32_t, int64_t> SymbolBlock(Reader* r, uint32_t count = 0) {
    const uint32_t n = r->VarUint();
    const int64_t min = r->VarSint();
    if (min < 0) Add("min_negative");
    if (n == 1) {
      Add("symbols_single");
      return {n, min};
    }
    Add("symbols_multi");
    if (n >= 256) Add("alphabet>=256");
    for (uint32_t i = 0; i < n; ++i) {
      if (r->VarUint() == 0) {
        Add("frequency_zero_run");
        i += r->VarUint();
      }
    }
    const uint32_t payload_size = r->VarUint();
    if (payload_size >= 4 && r->remaining() >= 4) {  // 5.2: an initial state below L_RANS
      const uint8_t* x = r->Here();
      if ((x[0] | x[1] << 8 | x[2] << 16 | uint32_t(x[3]) << 24) < (1u << 23)) {
        Add("rans_initial_state_low");
      }
    }
    if (count >= 4096) {  // 5.2: four interleaved states from version 0.4
      Add(version_minor >= 4 ? "rans_states=4" : "rans_states=1,count>=4096");
      EXPECT_GE(payload_size, version_minor >= 4 ? 16u : 4u);
    }
    r->Skip(payload_size);
    return {n, min};
  }

  // 5.4; set names the packet ("static", "dynamic", "added"). Returns the set's count.
  uint32_t GaussianSet(Reader* r, const std::string& set) {
    const uint32_t count = r->VarUint();
    Add(set + "_count" + (count == 0 ? "=0" : ">0"));
    if (count == 0) return 0;
    const int k = (sh_degree + 1) * (sh_degree + 1);
    const bool smallest_three = version_minor >= 5;
    const int components[6] = {3, 3, smallest_three ? 3 : 4, 1, 3, 3 * (k - 1)};
    const bool octree = version_minor >= 7;  // positions may be outside Draco (5.6)
    bool octree_used = false;
    int coded_before_rotation = 0;
    uint32_t rotation_bits = 0, position_bits = 0;
    int widths[6] = {0, 0, 0, 0, 0, 0};  // of the values adaptive_attributes() would code
    bool dc_codebook = false;
    for (int g = 0; g < (sh_degree > 0 ? 6 : 5); ++g) {
      const uint32_t bits = r->U8(), per_component = r->U8();
      widths[g] = static_cast<int>(bits);
      if (g == 0) position_bits = bits;
      if (g < 2 && bits > 0) ++coded_before_rotation;
      if (g == 2) rotation_bits = bits;
      if (bits == 0) Add("bits=0");
      if (bits == 1) Add("bits=1");
      if (bits >= 2 && bits <= 8) Add("bits=2..8");
      if (bits >= 9 && bits <= 16) Add("bits=9..16");
      if (bits >= 17) Add("bits=17..24");
      if (bits == 24) Add("bits=24");
      Add(per_component ? "per_component=1" : "per_component=0");
      for (int pair = 0; pair < (per_component ? components[g] : 1); ++pair) {
        const float min = r->F32();
        r->Skip(4);  // step
        // 5.4: min + 0 * step turns -0 into +0.
        if (bits == 0 && min == 0 && std::signbit(min)) Add("bits0_min_negative_zero");
      }
      if (version_minor >= 6) {
        const uint32_t size = Codebook(r, g, static_cast<uint32_t>(components[g]));
        if (size > 0 && bits > 0) widths[g] = IndexWidth(size);
        dc_codebook = dc_codebook || (g == 4 && size > 0);
      }
    }
    if (octree && position_bits > 0) {
      const uint32_t flag = r->U8();
      Add(flag ? "octree=1" : "octree=0");
      if (flag) Octree(r, count, static_cast<int>(position_bits));
      if (flag) --coded_before_rotation;  // positions are not a Draco attribute
      octree_used = flag != 0;
    }
    if (version_minor >= 8 && AdaptiveAttributes(r, widths, dc_codebook)) {
      // Draco holds the positions alone, when they are neither constant nor in the octree.
      const bool draco_present = position_bits > 0 && !octree_used;
      Add(draco_present ? "adaptive,draco=positions" : "adaptive,draco=absent");
      if (draco_present) {
        const uint32_t draco = r->VarUint();
        DracoPayload(r->Here(), draco);
        r->Skip(draco);
      }
      Add(rotation_bits > 0 ? "rotation=smallest_three" : "rotation=smallest_three,bits=0");
      return count;
    }
    const uint32_t draco = r->VarUint();
    if (smallest_three) {
      Add(rotation_bits > 0 ? "rotation=smallest_three" : "rotation=smallest_three,bits=0");
      if (rotation_bits > 0) RotationIndices(r->Here(), draco, coded_before_rotation + 1);
    } else if (rotation_bits > 0) {
      Add("rotation=four_components");
    }
    DracoPayload(r->Here(), draco);
    r->Skip(draco);
    return count;
  }

  // 5.4 (0.6): a group's codebook_size and entries. Returns the size.
  uint32_t Codebook(Reader* r, int group, uint32_t components) {
    const uint32_t size = r->VarUint();
    if (size == 0) {
      Add("codebook_size=0");
      return 0;
    }
    Add("codebook,group=" + std::to_string(group));
    Add(size <= 256 ? "codebook_index=uint8" : "codebook_index=uint16");
    if ((size & (size - 1)) != 0) Add("codebook_size_not_power_of_two");
    SymbolBlock(r, size * components);
    return size;
  }

  static int IndexWidth(uint32_t size) {
    int width = 0;
    while ((1u << width) < size) ++width;
    return width;
  }

  // 5.4, 5.7 (0.8): attribute_coding and, when 1, adaptive_attributes(). Returns the flag.
  bool AdaptiveAttributes(Reader* r, const int* widths, bool dc_codebook) {
    const uint32_t flag = r->U8();
    Add(flag ? "attribute_coding=1" : "attribute_coding=0");
    if (!flag) return false;
    // 5.7: scalar SH DC on the previous channel from 0.11, before on the neighbour and its own.
    if (widths[4] > 0 && !dc_codebook)
      Add(version_minor >= 11 ? "adaptive_dc=channel" : "adaptive_dc=own");
    for (int g = 1; g < 6; ++g) {
      if (widths[g] > 8) Add("adaptive_bypass_bits");  // 5.7: the bits below the tree's 8
      if (widths[g] > 0 && widths[g] < 3) Add("adaptive_width<3");
    }
    const uint32_t size = r->VarUint();
    Add(size == 4 ? "adaptive_size=4" : "adaptive_size>4");
    r->Skip(size);
    return true;
  }

  // 5.6 (0.7): octree_positions(), decoded by the SDK's reader to see its leaves.
  void Octree(Reader* r, uint32_t count, int bits) {
    m4d::ByteReader reader(r->Here(), r->remaining());
    std::vector<uint32_t> q(3 * static_cast<size_t>(count));
    ASSERT_TRUE(
        m4d::ReadOctreePositions(&reader, m4d::RansLayout::kInterleaved, count, bits, q.data())
            .ok());
    r->Skip(reader.position());
    for (uint32_t i = 1; i < count; ++i) {
      if (std::equal(&q[3 * i], &q[3 * i] + 3, &q[3 * (i - 1)])) Add("octree_repeats>0");
    }
  }

  // 5.5: a Draco payload's attributes, walked to their tagged symbols, whose tags the walk
  // decodes with Draco's rANS decoder: tag bits past the payload's end (they read as 0, the
  // next field starts at the end) and tags all 0 (no bit read, the next field starts at
  // tag_bits' first byte).
  void DracoPayload(const uint8_t* payload, uint32_t size) {
    if (payload == nullptr || size <= 16) return;  // no attribute
    Reader r(payload, size);
    r.Skip(11);  // magic, version, encoder type, method, flags
    const uint32_t count = r.U32();
    r.Skip(1);  // num_attribute_decoders
    const uint32_t num_attributes = r.U8();
    std::vector<uint32_t> components(num_attributes);
    for (uint32_t& c : components) {
      r.Skip(2);  // attribute_type, data_type
      c = r.U8();
      r.Skip(2);  // normalized, unique_id
    }
    r.Skip(num_attributes);  // decoder types
    for (uint32_t j = 0; j < num_attributes; ++j) {
      const bool delta = r.U8() == 0;
      r.Skip(delta ? 2 : 1);  // transform, compressed
      if (r.U8() == 1) {      // raw
        r.Skip(1);            // bit_length
        DracoFrequencies(&r, r.VarUint());
        r.Skip(r.VarUint());
      } else {
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(payload + size - r.remaining()), r.remaining(),
                    DRACO_BITSTREAM_VERSION(2, 3));
        draco::RAnsSymbolDecoder<5> tags;
        ASSERT_TRUE(tags.Create(&buffer) && tags.StartDecoding(&buffer));
        r.Skip(buffer.decoded_size());
        uint64_t bits = 0;
        for (uint32_t i = 0; i < count; ++i) bits += uint64_t{tags.DecodeSymbol()} * components[j];
        if (bits == 0) Add("draco_tags_all_zero");
        if (bits > 8 * uint64_t{r.remaining()}) Add("draco_tag_bits_past_payload");
        r.Skip(std::min<uint64_t>((bits + 7) / 8, r.remaining()));
      }
      if (delta) r.Skip(8);  // wrap_min, wrap_max
    }
    EXPECT_TRUE(r.done()) << "Draco payload not consumed";
  }

  static void DracoFrequencies(Reader* r, uint32_t n) {
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t t = r->U8();
      if ((t & 3) == 3) {
        i += t >> 2;  // a run of zeros
      } else {
        r->Skip(t & 3);
      }
    }
  }

  // 5.4: the indices of smallest-three rotations, Draco attribute `j` of the set's payload.
  void RotationIndices(const uint8_t* payload, uint32_t size, int j) {
    if (payload == nullptr) return;
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(payload), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
    ASSERT_TRUE(decoded.ok());
    const draco::PointAttribute* index = decoded.value()->attribute(j);
    ASSERT_NE(index, nullptr);
    ASSERT_EQ(index->num_components(), 1);
    for (uint32_t i = 0; i < decoded.value()->num_points(); ++i) {
      uint8_t k = 0;
      index->ConvertValue<uint8_t>(index->mapped_index(draco::PointIndex(i)), &k);
      Add("rotation_index=" + std::to_string(k));
    }
  }

  void SequenceHeader(Reader* r) {
    r->Skip(1);
    version_minor = r->U8();
    Add("version_minor=" + std::to_string(version_minor));
    r->Skip(1);
    sh_degree = static_cast<int>(r->U8());
    Add("sh_degree=" + std::to_string(sh_degree));
    r->Skip(12);
    levels = static_cast<int>(r->U8());
    Add("grid_levels=" + std::to_string(levels));
    uint64_t values = 0;
    std::vector<uint64_t> channels(levels);
    for (int l = 0; l < levels; ++l) {
      channels[l] = r->U8();
      if (channels[l] == 8) Add("grid_channels=8");
    }
    for (int l = 0; l < levels; ++l) {
      const uint64_t res = r->U16();
      if (res == 256) Add("grid_resolution=256");
      values += res * res * res * channels[l];
    }
    if (values == (1u << 24)) Add("grid_values=2^24");
    mlp_layers = static_cast<int>(r->U8());
    Add("mlp_hidden_layers=" + std::to_string(mlp_layers));
    if (r->U16() == 256) Add("mlp_width=256");
    if (version_minor >= 9) Add("up_axis=" + std::to_string(r->U8()));
  }

  void Mlp(Reader* r) {
    for (int tensor = 0; tensor < 2 * (mlp_layers + 1); ++tensor) {  // weights, biases
      if (!PowerOfTwo(r->F32())) Add("mlp_step_not_power_of_two");
      SymbolBlock(r);
    }
  }

  void MotionGrid(Reader* r) {
    r->Skip(24);
    bool any = false;
    for (int l = 0; l < levels; ++l) {
      const float step = r->F32();
      bool coded = false;
      if (version_minor >= 10) {  // the active voxels' values (0.10)
        const auto values = SymbolBlock(r);
        coded = values.first > 1 || values.second != 0;
        if (coded) Add("grid_active_values");
      } else {
        const auto flags = SymbolBlock(r);
        if (flags.first > 1) Add("bricks_mixed");
        if (flags.first == 1 && flags.second == 1) Add("bricks_all_one");
        coded = flags.first > 1 || flags.second == 1;
        SymbolBlock(r);
      }
      // 6.3 step 2 scales after the interpolation; only a level with values shows it.
      if (coded && !PowerOfTwo(step)) Add("grid_step_not_power_of_two");
      any = any || coded;
    }
    if (!any) Add("grid_all_zero");
  }

  void Appearance(Reader* r) {
    Add("appearance");
    if (!PowerOfTwo(r->F32())) Add("appearance_step_not_power_of_two");
    SymbolBlock(r, 3 * dynamic_count);
  }

  void Compensation(Reader* r) {
    const uint32_t removed = r->VarUint();
    Add(removed ? "removed>0" : "removed=0");
    if (removed) SymbolBlock(r, dynamic_count);
    dynamic_count = dynamic_count - removed + GaussianSet(r, "added");
  }

  void StartGop(bool random_access) {
    if (features.count("gop_started")) Add("gops>=2");
    if (random_access && features.count("random_access_started")) Add("random_access_gops>=2");
    Add("gop_started");
    if (random_access) Add("random_access_started");
    dependent = !random_access;
    if (dependent) Add("dependent_keyframe");
    static_in_gop = false;
    inter_in_gop = 0;
  }

  void Packet(const M4dPacketInfo& info, const uint8_t* payload) {
    Reader r(payload, info.payload_size);
    if (seen_packet && last_frame_index == 0xffffffffu && info.frame_index == 0) {
      Add("frame_index_wraps");  // spec 2: modulo 2^32
    }
    seen_packet = true;
    last_frame_index = info.frame_index;
    const bool starts_dependent = frame_complete && (info.type == M4D_PACKET_STATIC_UPDATE ||
                                                     info.type == M4D_PACKET_KEYFRAME_DYNAMIC);
    frame_complete = info.type == M4D_PACKET_MLP_WEIGHTS || info.type == M4D_PACKET_COMPENSATION;
    if (starts_dependent) StartGop(false);
    switch (info.type) {
      case M4D_PACKET_SEQUENCE_HEADER:
        StartGop(true);
        SequenceHeader(&r);
        break;
      case M4D_PACKET_KEYFRAME_STATIC:
        static_in_gop = true;
        GaussianSet(&r, "static");
        break;
      case M4D_PACKET_STATIC_UPDATE: {
        static_in_gop = true;
        const uint32_t removed = r.VarUint();
        Add(removed ? "static_update_removed>0" : "static_update_removed=0");
        if (removed) SymbolBlock(&r);
        GaussianSet(&r, "static_update_added");
        break;
      }
      case M4D_PACKET_KEYFRAME_DYNAMIC:
        if (!static_in_gop) Add(dependent ? "static_update_absent" : "keyframe_static_absent");
        dynamic_count = GaussianSet(&r, "dynamic");
        break;
      case M4D_PACKET_MLP_WEIGHTS:
        Mlp(&r);
        break;
      case M4D_PACKET_MOTION_GRID:
        if (++inter_in_gop >= 5) Add("inter_frames_in_gop>=5");
        MotionGrid(&r);
        break;
      case M4D_PACKET_APPEARANCE:
        Appearance(&r);
        break;
      case M4D_PACKET_COMPENSATION:
        Compensation(&r);
        break;
    }
    EXPECT_TRUE(r.done()) << "payload of type " << info.type << " not consumed";
    if (r.non_minimal()) Add("varuint_not_minimal");
  }
};

std::set<std::string> StreamFeatures(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> data((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  Walk walk;
  size_t pos = 0;
  while (pos < data.size()) {
    M4dPacketInfo info;
    if (m4d_parse_packet_header(&data[pos], data.size() - pos, &info) != M4D_OK) {
      ADD_FAILURE() << path << ": bad packet header at " << pos;
      break;
    }
    walk.Packet(info, &data[pos + 24]);
    pos += info.packet_size;
  }
  walk.features.erase("gop_started");
  walk.features.erase("random_access_started");
  return walk.features;
}

// Rows of coverage.md: feature -> streams.
std::map<std::string, std::vector<std::string>> CoverageRows() {
  std::ifstream in(kRoot + "/bitstream-spec/coverage.md");
  EXPECT_TRUE(in) << "no bitstream-spec/coverage.md";
  std::map<std::string, std::vector<std::string>> rows;
  // | section | element | `feature` | `stream`, `stream` |
  const std::regex row(R"(^\|[^|]*\|[^|]*\| `([^`]+)` \|(.*)\|\s*$)");
  const std::regex name("`([a-z0-9_]+)`");
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    const std::string streams = m[2].str();
    std::vector<std::string>& list = rows[m[1].str()];
    for (std::sregex_iterator it(streams.begin(), streams.end(), name), end; it != end; ++it) {
      list.push_back((*it)[1].str());
    }
  }
  return rows;
}

TEST(SpecCoverage, EveryRowHoldsAndEveryFeatureHasARow) {
  std::map<std::string, std::set<std::string>> features;  // stream -> features
  std::set<std::string> all;
  for (const auto& entry : std::filesystem::directory_iterator(kRoot + "/conformance/streams")) {
    if (entry.path().extension() != ".m4d") continue;
    const std::string stream = entry.path().stem().string();
    features[stream] = StreamFeatures(entry.path().string());
    all.insert(features[stream].begin(), features[stream].end());
  }
  const auto rows = CoverageRows();
  EXPECT_GE(rows.size(), 30u);
  for (const auto& [feature, streams] : rows) {
    EXPECT_FALSE(streams.empty()) << feature << ": no stream listed";
    for (const std::string& s : streams) {
      ASSERT_TRUE(features.count(s)) << feature << ": no conformance stream " << s;
      EXPECT_TRUE(features[s].count(feature)) << s << " does not exercise " << feature;
    }
  }
  for (const std::string& f : all) EXPECT_TRUE(rows.count(f)) << "no row for " << f;
  if (::testing::Test::HasFailure()) {
    for (const auto& [stream, set] : features) {
      std::ostringstream line;
      for (const std::string& f : set) line << f << ' ';
      std::printf("%s: %s\n", stream.c_str(), line.str().c_str());
    }
  }
}

}  // namespace
