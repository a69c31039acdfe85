// Encoding of adaptive_attributes() (bitstream-spec 5.7, version 0.8).
#ifndef M4D_ENCODER_LAYERS_ADAPTIVE_ATTRIBUTES_WRITER_H_
#define M4D_ENCODER_LAYERS_ADAPTIVE_ATTRIBUTES_WRITER_H_

#include <cstdint>
#include <vector>

#include "sdk/src/layers/adaptive_attributes.h"

namespace m4d {

// The payload of adaptive_attributes() for the fields' values (each below its limit), without
// its size field.
std::vector<uint8_t> EncodeAdaptiveAttributes(const AdaptiveField* fields, int num_fields,
                                              uint32_t count);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_ADAPTIVE_ATTRIBUTES_WRITER_H_
