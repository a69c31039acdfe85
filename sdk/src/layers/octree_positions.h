// Decoding of octree_positions() (bitstream-spec 5.6, version 0.7): a gaussian_set()'s
// quantized positions as the occupancy of an octree of depth `bits`, level by level, then how
// many Gaussians share each leaf. Why: Draco's sequential coder codes each coordinate's
// difference to the previous point in Morton order on its own, 21 bits per Gaussian on the
// default scene's keyframe at 12 bits a coordinate; one table of child masks per level takes
// 17.7 (Panoptic basketball: 18.4 against 14.7).
#ifndef M4D_SDK_LAYERS_OCTREE_POSITIONS_H_
#define M4D_SDK_LAYERS_OCTREE_POSITIONS_H_

#include <cstdint>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {

// Reads the octree of `count` positions at `bits` (1..24) bits a coordinate and writes their
// quantized coordinates, x y z per Gaussian in decoded (Morton) order, to q[0..3 * count).
// A node count above `count`, an empty child mask or repeats that do not add up to `count`
// fail with M4D_ERR_BITSTREAM before anything larger than `count` is allocated.
Status ReadOctreePositions(ByteReader* reader, RansLayout layout, uint32_t count, int bits,
                           uint32_t* q);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_OCTREE_POSITIONS_H_
