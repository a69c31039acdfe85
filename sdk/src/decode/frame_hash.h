// The normative frame hash (bitstream-spec section 7): MD5 over the output layers.
#ifndef M4D_SDK_DECODE_FRAME_HASH_H_
#define M4D_SDK_DECODE_FRAME_HASH_H_

#include <cstdint>
#include <string>

#include "m4d/m4d.h"
#include "sdk/src/decode/decoder.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_views.h"

namespace m4d {

// concealed_layers: M4D_LAYER_* bits of layers lost to damage, hashed as not output.
void FrameHash(const M4dGaussians& static_layer, const M4dGaussians& dynamic_layer,
               uint32_t concealed_layers, uint8_t md5[16]);

// Lowercase hex digest of a decoded frame, as conformance files list it.
std::string FrameHashHex(const DecodedFrame& frame);

}  // namespace m4d

#endif  // M4D_SDK_DECODE_FRAME_HASH_H_
