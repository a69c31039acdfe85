#include "sdk/src/decode/frame_hash.h"

#include <cstring>

#include "sdk/src/common/md5.h"

namespace m4d {
namespace {

void PutU32(uint32_t v, Md5* md5) {
  const uint8_t b[4] = {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8),
                        static_cast<uint8_t>(v >> 16), static_cast<uint8_t>(v >> 24)};
  md5->Update(b, 4);
}

// The hash is defined on little-endian bytes; a big-endian host swaps each float.
void PutFloats(const float* v, size_t n, Md5* md5) {
  if (!v || n == 0) return;
  const uint16_t probe = 1;
  uint8_t first_byte;
  std::memcpy(&first_byte, &probe, 1);
  if (first_byte == 1) {
    md5->Update(v, n * sizeof(float));
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    uint32_t bits;
    std::memcpy(&bits, v + i, 4);
    PutU32(bits, md5);
  }
}

void HashLayer(const M4dGaussians& g, Md5* md5) {
  const size_t n = g.count;
  PutU32(g.count, md5);
  PutU32(g.sh_degree, md5);
  PutFloats(g.positions, 3 * n, md5);
  PutFloats(g.log_scales, 3 * n, md5);
  PutFloats(g.rotations, 4 * n, md5);
  PutFloats(g.opacity_logits, n, md5);
  PutFloats(g.sh, 3 * static_cast<size_t>(g.sh_coefficients) * n, md5);
}

}  // namespace

void FrameHash(const M4dGaussians& static_layer, const M4dGaussians& dynamic_layer,
               uint32_t concealed_layers, uint8_t md5[16]) {
  // A concealed layer hashes as a layer not output (spec 7): its content is the decoder's.
  M4dGaussians none;
  std::memset(&none, 0, sizeof(none));
  Md5 hasher;
  HashLayer((concealed_layers & M4D_LAYER_STATIC) ? none : static_layer, &hasher);
  HashLayer((concealed_layers & M4D_LAYER_DYNAMIC) ? none : dynamic_layer, &hasher);
  hasher.Final(md5);
}

std::string FrameHashHex(const DecodedFrame& frame) {
  uint8_t digest[16];
  const GaussianSet empty;
  FrameHash(GaussianView(frame.static_layer ? *frame.static_layer : empty),
            GaussianView(frame.dynamic_layer ? *frame.dynamic_layer : empty), frame.concealed,
            digest);
  return HexDigest(digest);
}

}  // namespace m4d
