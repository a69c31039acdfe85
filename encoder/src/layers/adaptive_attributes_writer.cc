// Encoding of adaptive_attributes() (bitstream-spec 5.7).
#include "encoder/src/layers/adaptive_attributes_writer.h"

#include "encoder/src/entropy/binary_range_encoder.h"

namespace m4d {
namespace {

// The encoder's side of CodeAdaptiveValue: the bits of the value given are coded.
class EncodingCoder {
 public:
  explicit EncodingCoder(BinaryRangeEncoder* encoder) : encoder_(encoder) {}
  int Bit(BitProbability* p, uint32_t bit) {
    encoder_->EncodeBit(p, static_cast<int>(bit));
    return static_cast<int>(bit);
  }
  int Bypass(uint32_t bit) {
    encoder_->EncodeBypassBit(static_cast<int>(bit));
    return static_cast<int>(bit);
  }

 private:
  BinaryRangeEncoder* encoder_;
};

}  // namespace

std::vector<uint8_t> EncodeAdaptiveAttributes(const AdaptiveField* fields, int num_fields,
                                              uint32_t count) {
  AdaptiveAttributeModel model(fields, num_fields);
  BinaryRangeEncoder encoder;
  EncodingCoder coder(&encoder);
  CodeAdaptiveAttributes(&coder, fields, num_fields, count, &model);
  return encoder.Finish();
}

}  // namespace m4d
