// adaptive_attributes() (bitstream-spec 5.7).
#include "sdk/src/layers/adaptive_attributes.h"

#include <string>

namespace m4d {
namespace {

// The decoder's side of CodeAdaptiveValue: the bits come from the payload.
class DecodingCoder {
 public:
  explicit DecodingCoder(BinaryRangeDecoder* decoder) : decoder_(decoder) {}
  int Bit(BitProbability* p, uint32_t /*unused*/) { return decoder_->DecodeBit(p); }
  int Bypass(uint32_t /*unused*/) { return decoder_->DecodeBypassBit(); }

 private:
  BinaryRangeDecoder* decoder_;
};

}  // namespace

int CodebookIndexWidth(uint32_t codebook_size) {
  int width = 0;
  while ((1u << width) < codebook_size) ++width;
  return width;
}

static_assert(kAdaptiveContextBits <= kAdaptiveChannelBits,
              "a channel context's first component uses the neighbour's contexts");

uint32_t AdaptiveAttributeModel::Contexts(const AdaptiveField& field) {
  switch (field.context) {
    case AdaptiveContext::kNeighbourAndOwn:
      return 1u << (2 * kAdaptiveContextBits);
    case AdaptiveContext::kPreviousChannel:
      return 1u << kAdaptiveChannelBits;
    case AdaptiveContext::kNeighbour:
      break;
  }
  return 1u << kAdaptiveContextBits;
}

AdaptiveAttributeModel::AdaptiveAttributeModel(const AdaptiveField* fields, int num_fields) {
  size_t offset = 0;
  for (int f = 0; f < num_fields; ++f) {
    const int depth = fields[f].width < kAdaptiveTreeBits ? fields[f].width : kAdaptiveTreeBits;
    Layout l{offset, Contexts(fields[f]), size_t{1} << depth};
    offset += static_cast<size_t>(fields[f].components) * l.contexts * l.tree_size;
    layouts_.push_back(l);
  }
  probabilities_.assign(offset, BitProbability{1u << (kRangeProbabilityBits - 1)});
}

Status ReadAdaptiveAttributes(ByteReader* reader, const AdaptiveField* fields, int num_fields,
                              uint32_t count) {
  uint32_t size;
  const uint8_t* payload;
  if (!reader->ReadVarUint(&size) || size < 4 || !reader->ReadBytes(size, &payload)) {
    return BitstreamError("adaptive_attributes: size outside 4..remaining");
  }
  AdaptiveAttributeModel model(fields, num_fields);
  BinaryRangeDecoder decoder(payload, size);
  DecodingCoder coder(&decoder);
  if (!CodeAdaptiveAttributes(&coder, fields, num_fields, count, &model)) {
    return BitstreamError("adaptive_attributes: codebook index not below the codebook size");
  }
  if (!decoder.consumed_exactly()) {
    return BitstreamError(decoder.overran() ? "adaptive_attributes: payload too short"
                                            : "adaptive_attributes: trailing payload bytes");
  }
  return Status::Ok();
}

}  // namespace m4d
