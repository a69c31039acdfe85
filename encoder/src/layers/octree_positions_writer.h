// Encoding of octree_positions() (bitstream-spec 5.6, version 0.7): quantized positions as
// the child masks of an octree, one symbol block per level, then the Gaussians per leaf.
#ifndef M4D_ENCODER_LAYERS_OCTREE_POSITIONS_WRITER_H_
#define M4D_ENCODER_LAYERS_OCTREE_POSITIONS_WRITER_H_

#include <cstddef>
#include <cstdint>

#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {

// Morton order of quantized coordinates a and b (x y z): at each bit, from the top, z's bit
// is the most significant, then y's, then x's, as a node's child index (x | y << 1 | z << 2).
bool MortonLess(const uint32_t* a, const uint32_t* b);

// Writes octree_positions() of the n points whose coordinates (x y z at q[3 * i], each below
// 2^bits, bits 1..24) are in Morton order; the decoder returns them in that order.
Status WriteOctreePositions(const uint32_t* q, size_t n, int bits, RansLayout layout,
                            ByteWriter* out);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_OCTREE_POSITIONS_WRITER_H_
