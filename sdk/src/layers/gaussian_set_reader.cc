// Decoding of gaussian_set() (bitstream-spec 5.4, 5.5, 5.6, 5.7).
//
// Draco 1.5 trusts its input: a hostile stream can make it allocate from any count it
// declares (points, components, symbol tables). So the Draco stream's structure is walked
// first (CheckDracoStream) and only a stream whose every such count is bounded by the set's
// count and groups reaches draco::Decoder.
#include "sdk/src/layers/gaussian_set_reader.h"

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/entropy/symbol_decoding.h>
#include <draco/core/decoder_buffer.h>
#include <draco/point_cloud/point_cloud.h>

#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "sdk/src/common/spec_limits.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/adaptive_attributes.h"
#include "sdk/src/layers/octree_positions.h"

namespace m4d {
namespace {

constexpr int kMaxGroupComponents = 45;  // sh_rest at SH degree 3

// Draco stream profile of spec 5.5.
constexpr uint8_t kDracoVersionMajor = 2;
constexpr uint8_t kDracoVersionMinor = 3;
constexpr size_t kDracoHeaderSize = 11;  // "DRACO", version, encoder type, method, flags
// Draco's raw symbol scheme codes symbols below 2^18; its tagged scheme codes bit lengths
// 1..32. Larger tables are never written, and Draco would allocate them unchecked.
constexpr uint32_t kDracoMaxRawSymbols = 1u << 18;
constexpr uint32_t kDracoMaxTagSymbols = 32;
constexpr uint8_t kDracoMaxRawBitLength = 18;

// One attribute group's quantization (spec 5.4), (min, step) expanded to every component, and
// its codebook if it has one; or the index attribute of smallest-three rotations, which has no
// (min, step).
struct GroupCoding {
  int group = 0;
  int components = 0;
  int bits = 0;
  bool rotation_index = false;
  float min[kMaxGroupComponents];
  float step[kMaxGroupComponents];
  uint32_t codebook_size = 0;   // 0: scalar values
  std::vector<float> codebook;  // dequantized entries, [entry][component]
  // The attribute's values when they are not in Draco: octree positions (0.7), adaptive
  // attributes (0.8).
  std::vector<uint32_t> q;
};

draco::DataType DracoDataType(int bits) {
  return bits <= 8 ? draco::DT_UINT8 : bits <= 16 ? draco::DT_UINT16 : draco::DT_UINT32;
}

// The Draco attribute of a group (spec 5.5): its quantized components, or one codebook index.
int AttributeComponents(const GroupCoding& g) { return g.codebook_size > 0 ? 1 : g.components; }

draco::DataType AttributeDataType(const GroupCoding& g) {
  if (g.codebook_size > 0) return g.codebook_size <= 256 ? draco::DT_UINT8 : draco::DT_UINT16;
  return DracoDataType(g.bits);
}

// Every value of the attribute is below this.
uint32_t AttributeLimit(const GroupCoding& g) {
  return g.codebook_size > 0 ? g.codebook_size : 1u << g.bits;
}

draco::GeometryAttribute::Type DracoAttributeType(int group) {
  return group == kGroupPosition ? draco::GeometryAttribute::POSITION
                                 : draco::GeometryAttribute::GENERIC;
}

Status DracoError(const std::string& what) { return BitstreamError("Draco payload: " + what); }
Status DracoTruncated() { return DracoError("truncated"); }

// Skips the frequency table of a Draco rANS symbol coder with `num_symbols` entries.
Status SkipDracoFrequencyTable(ByteReader* r, uint32_t num_symbols) {
  for (uint32_t i = 0; i < num_symbols; ++i) {
    uint8_t token;
    if (!r->ReadU8(&token)) return DracoTruncated();
    if ((token & 3) == 3) {
      const uint32_t extra_zeros = token >> 2;
      if (extra_zeros >= num_symbols - i) return DracoError("frequency run past the table");
      i += extra_zeros;
    } else {
      const uint8_t* skipped;
      if (!r->ReadBytes(token & 3, &skipped)) return DracoTruncated();
    }
  }
  return Status::Ok();
}

// Skips the payload of a Draco rANS coder (spec 5.5: draco_rans). Its last byte's top two
// bits k say how many bytes before it hold the initial state: Draco reads them unchecked.
Status SkipDracoRansPayload(ByteReader* r) {
  uint32_t num_bytes;
  const uint8_t* bytes;
  if (!r->ReadVarUint(&num_bytes) || !r->ReadBytes(num_bytes, &bytes)) return DracoTruncated();
  if (num_bytes < 1 || num_bytes < 1u + (bytes[num_bytes - 1] >> 6)) {
    return DracoError("rANS payload shorter than its initial state");
  }
  return Status::Ok();
}

// Skips one array coded by Draco's DecodeSymbols (`num_values` values in entries of
// `components`) at r's position in `payload` (of `size` bytes), after bounding its tables.
Status SkipDracoSymbols(const uint8_t* payload, size_t size, ByteReader* r, uint32_t num_values,
                        int components, std::vector<uint32_t>* scratch) {
  const size_t start = r->position();
  uint8_t scheme;
  if (!r->ReadU8(&scheme)) return DracoTruncated();
  if (scheme == draco::SYMBOL_CODING_RAW) {
    uint8_t bit_length;
    uint32_t num_symbols;
    if (!r->ReadU8(&bit_length) || !r->ReadVarUint(&num_symbols)) return DracoTruncated();
    if (bit_length < 1 || bit_length > kDracoMaxRawBitLength) {
      return DracoError("bad symbol bit length");
    }
    if (num_symbols < 1 || num_symbols > kDracoMaxRawSymbols) {
      return DracoError("symbol table too large");
    }
    M4D_RETURN_IF_ERROR(SkipDracoFrequencyTable(r, num_symbols));
    return SkipDracoRansPayload(r);
  }
  if (scheme != draco::SYMBOL_CODING_TAGGED) return DracoError("unknown symbol coding");
  uint32_t num_tags;
  if (!r->ReadVarUint(&num_tags)) return DracoTruncated();
  if (num_tags < 1 || num_tags > kDracoMaxTagSymbols) return DracoError("tag table too large");
  ByteReader tags = *r;
  M4D_RETURN_IF_ERROR(SkipDracoFrequencyTable(&tags, num_tags));
  M4D_RETURN_IF_ERROR(SkipDracoRansPayload(&tags));
  // The tagged values' length is known only once the tags are decoded: let Draco decode the
  // array, whose tables are now bounded.
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(payload + start), size - start,
              DRACO_BITSTREAM_VERSION(kDracoVersionMajor, kDracoVersionMinor));
  scratch->resize(num_values);
  if (!draco::DecodeSymbols(num_values, components, &buffer, scratch->data())) {
    return DracoError("bad tagged symbols");
  }
  const size_t consumed = static_cast<size_t>(buffer.decoded_size());
  const size_t read = r->position() - start;
  const uint8_t* skipped;
  if (consumed < read || !r->ReadBytes(consumed - read, &skipped)) return DracoTruncated();
  return Status::Ok();
}

// Walks the Draco stream up to where the cost of decoding is bounded by `count` and the coded
// groups (spec 5.5): header, point count, attribute descriptors and every attribute's
// prediction, symbol tables and wrap bounds (to the exact end).
Status CheckDracoStream(const uint8_t* payload, size_t size, uint32_t count,
                        const GroupCoding* const* coded, int num_coded) {
  ByteReader r(payload, size);
  const uint8_t* header;
  if (!r.ReadBytes(kDracoHeaderSize, &header)) return DracoTruncated();
  if (std::memcmp(header, "DRACO", 5) != 0) return DracoError("no DRACO magic");
  if (header[5] != kDracoVersionMajor || header[6] != kDracoVersionMinor) {
    return DracoError("version " + std::to_string(header[5]) + "." + std::to_string(header[6]) +
                      " is not 2.3");
  }
  if (header[7] != draco::POINT_CLOUD) return DracoError("not a point cloud");
  // Sequential only: its decoded order is the coded order, and its tables can be bounded.
  if (header[8] != draco::POINT_CLOUD_SEQUENTIAL_ENCODING) {
    return DracoError("encoding method " + std::to_string(header[8]) + " is not sequential");
  }
  if (header[9] != 0 || header[10] != 0) return DracoError("flags (metadata) set");

  uint32_t num_points;
  uint8_t num_decoders;
  if (!r.ReadU32(&num_points) || !r.ReadU8(&num_decoders)) return DracoTruncated();
  if (num_points != count) {
    return DracoError("declares " + std::to_string(num_points) + " points, the set " +
                      std::to_string(count));
  }
  if (num_decoders != (num_coded > 0 ? 1 : 0)) return DracoError("wrong attribute decoder count");
  if (num_coded == 0) return r.remaining() == 0 ? Status::Ok() : DracoError("trailing bytes");

  // Descriptors: one attribute per coded group, in group order, each in a single byte where
  // Draco writes a varint (all values here are below 128).
  uint8_t num_attributes;
  if (!r.ReadU8(&num_attributes)) return DracoTruncated();
  if (num_attributes != num_coded) return DracoError("wrong attribute count");
  for (int j = 0; j < num_coded; ++j) {
    const uint8_t* d;
    if (!r.ReadBytes(5, &d)) return DracoTruncated();
    const GroupCoding& g = *coded[j];
    if (d[0] != DracoAttributeType(g.group) || d[1] != AttributeDataType(g) ||
        d[2] != AttributeComponents(g) || d[3] != 0 || d[4] != j) {
      return DracoError("attribute " + std::to_string(j) + " does not match group " +
                        std::to_string(g.group));
    }
  }

  for (int j = 0; j < num_coded; ++j) {
    uint8_t decoder_type;
    if (!r.ReadU8(&decoder_type)) return DracoTruncated();
    if (decoder_type != draco::SEQUENTIAL_ATTRIBUTE_ENCODER_INTEGER) {
      return DracoError("attribute not integer-coded");
    }
  }
  std::vector<uint32_t> scratch;
  for (int j = 0; j < num_coded; ++j) {
    const GroupCoding& g = *coded[j];
    uint8_t prediction, compressed;
    if (!r.ReadU8(&prediction)) return DracoTruncated();
    const bool delta = prediction == draco::PREDICTION_DIFFERENCE;
    if (!delta && static_cast<int8_t>(prediction) != draco::PREDICTION_NONE) {
      return DracoError("unsupported prediction scheme");
    }
    if (delta) {
      uint8_t transform;
      if (!r.ReadU8(&transform)) return DracoTruncated();
      if (transform != draco::PREDICTION_TRANSFORM_WRAP) {
        return DracoError("bad prediction transform");
      }
    }
    if (!r.ReadU8(&compressed)) return DracoTruncated();
    if (compressed != 1) return DracoError("uncompressed attribute");
    const int components = AttributeComponents(g);
    M4D_RETURN_IF_ERROR(SkipDracoSymbols(
        payload, size, &r, count * static_cast<uint32_t>(components), components, &scratch));
    if (delta) {
      uint32_t lo, hi;
      if (!r.ReadU32(&lo) || !r.ReadU32(&hi)) return DracoTruncated();
      if (lo > hi || hi >= AttributeLimit(g)) return DracoError("bad wrap bounds");
    }
  }
  return r.remaining() == 0 ? Status::Ok() : DracoError("trailing bytes");
}

template <typename T>
bool Dequantize(const uint8_t* src, uint32_t count, const GroupCoding& g, float* dst,
                size_t dst_stride) {
  const int c = g.components;
  const uint32_t limit = 1u << g.bits;
  for (uint32_t i = 0; i < count; ++i, src += c * sizeof(T), dst += dst_stride) {
    for (int r = 0; r < c; ++r) {
      T q;
      std::memcpy(&q, src + r * sizeof(T), sizeof(T));
      if (static_cast<uint32_t>(q) >= limit) return false;
      dst[r] = g.min[r] + static_cast<float>(q) * g.step[r];
    }
  }
  return true;
}

// A codebook group: each Gaussian's index selects an entry, dequantized once (spec 5.4).
template <typename T>
bool LookUp(const uint8_t* src, uint32_t count, const GroupCoding& g, float* dst,
            size_t dst_stride) {
  const size_t bytes = sizeof(float) * static_cast<size_t>(g.components);
  for (uint32_t i = 0; i < count; ++i, src += sizeof(T), dst += dst_stride) {
    T k;
    std::memcpy(&k, src, sizeof(T));
    if (static_cast<uint32_t>(k) >= g.codebook_size) return false;
    std::memcpy(dst, &g.codebook[static_cast<size_t>(k) * g.components], bytes);
  }
  return true;
}

// Where a group's components go in the set: base pointer and stride per Gaussian.
float* GroupDestination(GaussianSet* set, int group, size_t* stride) {
  const size_t sh_stride = static_cast<size_t>(set->sh_floats());
  switch (group) {
    case kGroupPosition:
      *stride = 3;
      return set->positions.data();
    case kGroupLogScale:
      *stride = 3;
      return set->log_scales.data();
    case kGroupRotation:
      *stride = 4;
      return set->rotations.data();
    case kGroupOpacity:
      *stride = 1;
      return set->opacity_logits.data();
    case kGroupShDc:
      *stride = sh_stride;
      return set->sh.data();
    default:
      *stride = sh_stride;
      return set->sh.data() + 3;
  }
}

// Checks that Draco returned the attributes CheckDracoStream saw, as dense arrays of `count`.
const uint8_t* AttributeValues(const draco::PointCloud& pc, int j, const GroupCoding& g,
                               uint32_t count) {
  const draco::PointAttribute* att = pc.attribute(j);
  if (att == nullptr || att->attribute_type() != DracoAttributeType(g.group) ||
      att->data_type() != AttributeDataType(g) || att->num_components() != AttributeComponents(g) ||
      !att->is_mapping_identity() || att->size() != count || att->byte_offset() != 0) {
    return nullptr;
  }
  const size_t stride = static_cast<size_t>(draco::DataTypeLength(att->data_type())) *
                        static_cast<size_t>(AttributeComponents(g));
  if (static_cast<size_t>(att->byte_stride()) != stride ||
      att->buffer()->data_size() < stride * count) {
    return nullptr;
  }
  return att->buffer()->data();
}

// Rotations coded as their three smallest components (spec 5.4): the three were dequantized
// into slots 0..2 of each quaternion; `index` (null when the rotation group has bits 0, which
// means index 0 throughout) places them and the recovered largest component.
template <typename T>
Status ComposeRotations(const T* index, uint32_t count, float* rotations) {
  for (uint32_t i = 0; i < count; ++i, rotations += 4) {
    const uint32_t k = index != nullptr ? index[i] : 0;
    if (k > 3) return BitstreamError("rotation index above 3");
    ComposeSmallestThree(rotations, static_cast<int>(k), rotations);
  }
  return Status::Ok();
}

// The groups Draco codes: those with bits whose values are not decoded already.
int DracoGroups(const GroupCoding* groups, int num_groups, const GroupCoding** coded) {
  int num_coded = 0;
  for (int k = 0; k < num_groups; ++k) {
    if (groups[k].bits > 0 && groups[k].q.empty()) coded[num_coded++] = &groups[k];
  }
  return num_coded;
}

// Decodes the Draco payload of the groups `coded` into `pc`.
Status DecodeDraco(const uint8_t* payload, size_t size, uint32_t count,
                   const GroupCoding* const* coded, int num_coded,
                   std::unique_ptr<draco::PointCloud>* out) {
  std::unique_ptr<draco::PointCloud> pc;
  try {
    M4D_RETURN_IF_ERROR(CheckDracoStream(payload, size, count, coded, num_coded));
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(payload), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
    if (!decoded.ok()) return DracoError(decoded.status().error_msg_string());
    if (buffer.remaining_size() != 0) return DracoError("trailing bytes");
    pc = std::move(decoded).value();
  } catch (const std::bad_alloc&) {
    return Status(M4D_ERR_NOMEM, "out of memory in the Draco decoder");
  } catch (...) {
    return DracoError("the Draco decoder failed");
  }
  if (pc == nullptr || pc->num_points() != count || pc->num_attributes() != num_coded) {
    return DracoError("decoded point cloud does not match the set");
  }
  *out = std::move(pc);
  return Status::Ok();
}

// Dequantizes every group into `out`: from the Draco point cloud `pc` (null when Draco codes
// no group) or from the values decoded outside it.
Status DecodeGroups(const draco::PointCloud* pc, uint32_t count, const GroupCoding* groups,
                    int num_groups, int sh_degree, GaussianSet* out) {
  const GroupCoding* coded[kNumGaussianGroups + 1];
  const int num_coded = DracoGroups(groups, num_groups, coded);
  const uint8_t* values[kNumGaussianGroups + 1];
  for (int j = 0; j < num_coded; ++j) {
    values[j] = AttributeValues(*pc, j, *coded[j], count);
    if (values[j] == nullptr) {
      return DracoError("decoded attribute " + std::to_string(j) + " is malformed");
    }
  }
  bool smallest_three = false;
  for (int k = 0; k < num_groups; ++k) smallest_three = smallest_three || groups[k].rotation_index;

  out->sh_degree = sh_degree;
  out->Resize(count);
  const uint8_t* rotation_index = nullptr;
  const uint32_t* adaptive_rotation_index = nullptr;
  int j = 0;
  for (int k = 0; k < num_groups; ++k) {
    const GroupCoding& g = groups[k];
    if (g.rotation_index) {
      if (g.bits > 0 && !g.q.empty()) {
        adaptive_rotation_index = g.q.data();
      } else if (g.bits > 0) {
        rotation_index = values[j++];  // UINT8, one component
      }
      continue;
    }
    size_t stride;
    float* dst = GroupDestination(out, g.group, &stride);
    if (g.bits == 0) {
      // q = 0: the spec formula still applies (min = -0 gives +0).
      float value[kMaxGroupComponents];
      for (int r = 0; r < g.components; ++r) value[r] = g.min[r] + 0.0f * g.step[r];
      for (uint32_t i = 0; i < count; ++i, dst += stride) {
        std::memcpy(dst, value, sizeof(float) * static_cast<size_t>(g.components));
      }
      continue;
    }
    if (!g.q.empty()) {
      // Below 2^bits or the codebook size: checked as they were decoded.
      const uint8_t* q = reinterpret_cast<const uint8_t*>(g.q.data());
      if (g.codebook_size > 0) {
        LookUp<uint32_t>(q, count, g, dst, stride);
      } else {
        Dequantize<uint32_t>(q, count, g, dst, stride);
      }
      continue;
    }
    bool ok;
    switch (AttributeDataType(g)) {
      case draco::DT_UINT8:
        ok = g.codebook_size > 0 ? LookUp<uint8_t>(values[j], count, g, dst, stride)
                                 : Dequantize<uint8_t>(values[j], count, g, dst, stride);
        break;
      case draco::DT_UINT16:
        ok = g.codebook_size > 0 ? LookUp<uint16_t>(values[j], count, g, dst, stride)
                                 : Dequantize<uint16_t>(values[j], count, g, dst, stride);
        break;
      default:
        ok = Dequantize<uint32_t>(values[j], count, g, dst, stride);
        break;
    }
    if (!ok) {
      return BitstreamError("group " + std::to_string(g.group) + ": value not below " +
                            (g.codebook_size > 0
                                 ? "the codebook size " + std::to_string(g.codebook_size)
                                 : "2^" + std::to_string(g.bits)));
    }
    ++j;
  }
  if (!smallest_three) return Status::Ok();
  return adaptive_rotation_index != nullptr
             ? ComposeRotations(adaptive_rotation_index, count, out->rotations.data())
             : ComposeRotations(rotation_index, count, out->rotations.data());
}

// codebook_size and, when not 0, the entries of group `g` (version 0.6, spec 5.4), dequantized
// once with the group's (min, step).
Status ReadCodebook(ByteReader* reader, RansLayout layout, const std::string& where,
                    GroupCoding* g) {
  uint32_t size;
  if (!reader->ReadVarUint(&size)) return BitstreamError(where + "truncated codebook_size");
  if (size == 0) return Status::Ok();
  if (size > kMaxCodebookSize) {
    return LimitError(where + "codebook of " + std::to_string(size) + " entries exceeds " +
                      std::to_string(kMaxCodebookSize));
  }
  if (size < 2 || !GroupAllowsCodebook(g->group) || g->bits < 1 || g->bits > kMaxCodebookBits) {
    return BitstreamError(where +
                          "codebook of size 1, of a group without codebooks, or with bits "
                          "outside 1..12");
  }
  const size_t c = static_cast<size_t>(g->components);
  const uint32_t num_values = size * static_cast<uint32_t>(c);
  std::vector<int32_t> q(num_values);
  M4D_RETURN_IF_ERROR(ReadSymbolBlock(reader, layout, num_values, 0, (1 << g->bits) - 1, q.data()));
  g->codebook_size = size;
  g->codebook.resize(num_values);
  for (size_t k = 0; k < num_values; ++k) {
    const size_t r = k % c;
    g->codebook[k] = g->min[r] + static_cast<float>(q[k]) * g->step[r];
  }
  return Status::Ok();
}

// adaptive_attributes() (version 0.8, spec 5.7): every group but the positions with bits, and
// the rotation index, decoded into the groups' q.
Status ReadAdaptiveGroups(ByteReader* reader, const GaussianSetSyntax& syntax, uint32_t count,
                          GroupCoding* groups, int num_groups) {
  AdaptiveField fields[kNumGaussianGroups + 1];
  int num_fields = 0;
  for (int k = 0; k < num_groups; ++k) {
    GroupCoding& g = groups[k];
    if (g.group == kGroupPosition || g.bits == 0) continue;
    AdaptiveField& field = fields[num_fields++];
    field.components = AttributeComponents(g);
    field.width = g.codebook_size > 0 ? CodebookIndexWidth(g.codebook_size) : g.bits;
    field.limit = AttributeLimit(g);
    field.context = AdaptiveContextOf(g.group, g.codebook_size > 0, g.rotation_index, syntax);
    g.q.resize(static_cast<size_t>(count) * static_cast<size_t>(field.components));
    field.q = g.q.data();
  }
  return ReadAdaptiveAttributes(reader, fields, num_fields, count);
}

}  // namespace

AdaptiveContext AdaptiveContextOf(int group, bool codebook, bool rotation_index,
                                  const GaussianSetSyntax& syntax) {
  if (codebook || rotation_index) return AdaptiveContext::kNeighbour;
  if (group == kGroupShDc && syntax.sh_dc_channel_context) return AdaptiveContext::kPreviousChannel;
  const bool own = group == kGroupLogScale || group == kGroupRotation || group == kGroupShDc;
  return own ? AdaptiveContext::kNeighbourAndOwn : AdaptiveContext::kNeighbour;
}

bool GroupAllowsCodebook(int group) {
  return group == kGroupLogScale || group == kGroupShDc || group == kGroupShRest;
}

int GaussianGroupComponents(int group, int sh_degree) {
  switch (group) {
    case kGroupPosition:
    case kGroupLogScale:
    case kGroupShDc:
      return 3;
    case kGroupRotation:
      return 4;
    case kGroupOpacity:
      return 1;
    case kGroupShRest:
      return 3 * (ShCoefficients(sh_degree) - 1);
    default:
      return 0;
  }
}

int CodedGroupComponents(int group, int sh_degree, RotationCoding rotation) {
  if (group == kGroupRotation && rotation == RotationCoding::kSmallestThree) return 3;
  return GaussianGroupComponents(group, sh_degree);
}

Status ReadGaussianSet(ByteReader* reader, int sh_degree, const GaussianSetSyntax& syntax,
                       uint32_t max_count, GaussianSet* out) {
  const RotationCoding rotation = syntax.rotation;
  if (sh_degree < 0 || sh_degree > 3) return Status(M4D_ERR_INVALID_ARG, "bad SH degree");
  uint32_t count;
  if (!reader->ReadVarUint(&count)) return BitstreamError("gaussian_set: bad count");
  if (count > max_count || count > kMaxGaussiansPerSet) {
    return LimitError(
        "gaussian_set: " + std::to_string(count) + " Gaussians exceed the limit " +
        std::to_string(max_count < kMaxGaussiansPerSet ? max_count : kMaxGaussiansPerSet));
  }
  if (count == 0) {
    out->sh_degree = sh_degree;
    out->Resize(0);
    return Status::Ok();
  }

  GroupCoding groups[kNumGaussianGroups + 1];
  int num_groups = 0;
  for (int group = 0; group < kNumGaussianGroups; ++group) {
    const int components = CodedGroupComponents(group, sh_degree, rotation);
    if (components == 0) continue;
    GroupCoding& g = groups[num_groups++];
    g.group = group;
    g.components = components;
    const std::string where = "gaussian_set group " + std::to_string(group) + ": ";
    uint8_t bits, per_component;
    if (!reader->ReadU8(&bits) || !reader->ReadU8(&per_component)) {
      return BitstreamError(where + "truncated");
    }
    if (bits > kMaxAttributeBits) return BitstreamError(where + "bits above 24");
    if (per_component > 1) return BitstreamError(where + "per_component not 0 or 1");
    g.bits = bits;
    const int pairs = per_component ? components : 1;
    for (int p = 0; p < pairs; ++p) {
      if (!reader->ReadFiniteF32(&g.min[p]) || !reader->ReadFiniteF32(&g.step[p])) {
        return BitstreamError(where + "truncated or non-finite min/step");
      }
      if (!(g.step[p] >= 0.0f)) return BitstreamError(where + "negative step");
    }
    for (int r = pairs; r < components; ++r) {
      g.min[r] = g.min[0];
      g.step[r] = g.step[0];
    }
    if (syntax.codebooks) M4D_RETURN_IF_ERROR(ReadCodebook(reader, syntax.rans_layout, where, &g));
    if (group == kGroupRotation && rotation == RotationCoding::kSmallestThree) {
      // Its Draco attribute follows the rotation's when the rotation group is coded.
      GroupCoding& index = groups[num_groups++];
      index.group = kGroupRotation;
      index.components = 1;
      index.bits = g.bits > 0 ? kRotationIndexBits : 0;
      index.rotation_index = true;
    }
  }

  uint8_t octree = 0;
  if (syntax.octree_positions && groups[kGroupPosition].bits > 0 &&
      (!reader->ReadU8(&octree) || octree > 1)) {
    return BitstreamError("gaussian_set: octree flag truncated or not 0 or 1");
  }
  if (octree) {
    GroupCoding& g = groups[kGroupPosition];
    g.q.resize(3 * static_cast<size_t>(count));
    M4D_RETURN_IF_ERROR(ReadOctreePositions(reader, syntax.rans_layout, count, g.bits, g.q.data()));
  }
  uint8_t adaptive = 0;
  if (syntax.adaptive_attributes && (!reader->ReadU8(&adaptive) || adaptive > 1)) {
    return BitstreamError("gaussian_set: attribute_coding truncated or not 0 or 1");
  }
  if (adaptive) M4D_RETURN_IF_ERROR(ReadAdaptiveGroups(reader, syntax, count, groups, num_groups));

  const GroupCoding* coded[kNumGaussianGroups + 1];
  const int num_coded = DracoGroups(groups, num_groups, coded);
  std::unique_ptr<draco::PointCloud> pc;
  if (num_coded > 0 || !adaptive) {  // before 0.8 a payload is always present
    uint32_t draco_size;
    const uint8_t* draco_payload;
    if (!reader->ReadVarUint(&draco_size) || draco_size == 0 ||
        !reader->ReadBytes(draco_size, &draco_payload)) {
      return BitstreamError("gaussian_set: draco_size outside 1..remaining");
    }
    M4D_RETURN_IF_ERROR(DecodeDraco(draco_payload, draco_size, count, coded, num_coded, &pc));
  }
  return DecodeGroups(pc.get(), count, groups, num_groups, sh_degree, out);
}

}  // namespace m4d
