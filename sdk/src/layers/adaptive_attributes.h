// adaptive_attributes() (bitstream-spec 5.7, version 0.8): the attribute groups of a Gaussian
// set coded with adaptive binary range coding, each value conditioned on its neighbour in
// coding order or on the Gaussian's previous component. The traversal and the context model are
// shared by the decoder and the encoder, which differ only in their coder.
#ifndef M4D_SDK_LAYERS_ADAPTIVE_ATTRIBUTES_H_
#define M4D_SDK_LAYERS_ADAPTIVE_ATTRIBUTES_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/binary_range_decoder.h"

namespace m4d {

// What a field's component r is conditioned on (spec 5.7).
enum class AdaptiveContext {
  kNeighbour,        // the previous Gaussian's component r
  kNeighbourAndOwn,  // that, and for r > 0 this Gaussian's component r - 1
  kPreviousChannel,  // r = 0: the previous Gaussian's; r > 0: this Gaussian's r - 1 only (0.11)
};

// One field of adaptive_attributes(): a group's quantized values or codebook indices, or the
// rotation index of smallest-three rotations.
struct AdaptiveField {
  int components = 0;  // values per Gaussian
  int width = 0;       // bits per value, 1..24
  AdaptiveContext context = AdaptiveContext::kNeighbour;
  uint32_t limit = 0;     // every value is below this: 2^width, or the codebook size
  uint32_t* q = nullptr;  // [i * components + r], i in coding order
};

// Bits of a codebook index: the smallest w with 2^w >= size (size >= 2).
int CodebookIndexWidth(uint32_t codebook_size);

// The probability trees of every field's components and contexts, all starting at 1/2.
class AdaptiveAttributeModel {
 public:
  AdaptiveAttributeModel(const AdaptiveField* fields, int num_fields);

  BitProbability* Tree(int field, int component, uint32_t context) {
    const Layout& l = layouts_[static_cast<size_t>(field)];
    return &probabilities_[l.offset +
                           (static_cast<size_t>(component) * l.contexts + context) * l.tree_size];
  }
  // Contexts of one component of a field: 8 (the neighbour's top bits), times 8 with an own
  // context, 32 (the previous channel's top bits) for a channel context.
  static uint32_t Contexts(const AdaptiveField& field);

 private:
  struct Layout {
    size_t offset;
    uint32_t contexts;
    size_t tree_size;
  };
  std::vector<Layout> layouts_;
  std::vector<BitProbability> probabilities_;
};

// Codes one value of `width` bits: its kAdaptiveTreeBits most significant bits down the bit
// tree `tree` (node 1 the root, node n's children 2n and 2n + 1), the others as bypass bits.
// The decoder's coder ignores `value`; the encoder's codes it. Returns the value coded.
template <typename Coder>
inline uint32_t CodeAdaptiveValue(Coder* coder, BitProbability* tree, int width, uint32_t value) {
  const int depth = width < kAdaptiveTreeBits ? width : kAdaptiveTreeBits;
  uint32_t node = 1;
  for (int k = 1; k <= depth; ++k) {
    node = 2 * node + static_cast<uint32_t>(coder->Bit(&tree[node], (value >> (width - k)) & 1));
  }
  uint32_t v = node - (1u << depth);
  for (int k = depth + 1; k <= width; ++k) {
    v = 2 * v + static_cast<uint32_t>(coder->Bypass((value >> (width - k)) & 1));
  }
  return v;
}

// The shift that leaves a value of `width` bits its top `bits` bits.
inline int TopBitsShift(int width, int bits) { return width < bits ? 0 : width - bits; }

// Codes the fields one after the other; within a field the Gaussians in coding order, each
// Gaussian's components in order. Component r of Gaussian i is coded with the tree of its
// field's context (AdaptiveContext): top bits of component r of Gaussian i - 1, and of
// component r - 1 of Gaussian i. False when a value reaches its field's limit.
template <typename Coder>
bool CodeAdaptiveAttributes(Coder* coder, const AdaptiveField* fields, int num_fields,
                            uint32_t count, AdaptiveAttributeModel* model) {
  for (int f = 0; f < num_fields; ++f) {
    const AdaptiveField& field = fields[f];
    const int shift = TopBitsShift(field.width, kAdaptiveContextBits);
    const int channel_shift = TopBitsShift(field.width, kAdaptiveChannelBits);
    const bool own = field.context == AdaptiveContext::kNeighbourAndOwn;
    const bool channel = field.context == AdaptiveContext::kPreviousChannel;
    const uint32_t own_contexts = own ? 1u << kAdaptiveContextBits : 1u;
    const size_t c = static_cast<size_t>(field.components);
    for (uint32_t i = 0; i < count; ++i) {
      uint32_t* q = field.q + i * c;
      const uint32_t* previous = i > 0 ? q - c : nullptr;  // the previous Gaussian's values
      for (size_t r = 0; r < c; ++r) {
        uint32_t context = previous != nullptr ? (previous[r] >> shift) * own_contexts : 0;
        if (own && r > 0) context += q[r - 1] >> shift;
        if (channel && r > 0) context = q[r - 1] >> channel_shift;
        BitProbability* tree = model->Tree(f, static_cast<int>(r), context);
        q[r] = CodeAdaptiveValue(coder, tree, field.width, q[r]);
        if (q[r] >= field.limit) return false;
      }
    }
  }
  return true;
}

// Reads adaptive_attributes(): a varuint payload size, then the payload, decoded into the
// fields' q arrays (each of count * components values).
Status ReadAdaptiveAttributes(ByteReader* reader, const AdaptiveField* fields, int num_fields,
                              uint32_t count);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_ADAPTIVE_ATTRIBUTES_H_
