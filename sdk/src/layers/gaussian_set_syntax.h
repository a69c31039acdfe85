// What gaussian_set() holds in a given bitstream version (bitstream-spec 5.4, 10): the readers
// and writers of every version share one implementation, told the version's syntax.
#ifndef M4D_SDK_LAYERS_GAUSSIAN_SET_SYNTAX_H_
#define M4D_SDK_LAYERS_GAUSSIAN_SET_SYNTAX_H_

#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/rotation_coding.h"

namespace m4d {

// Defaults are the newest version's.
struct GaussianSetSyntax {
  RotationCoding rotation = RotationCoding::kSmallestThree;  // smallest-three from 0.5 on
  bool codebooks = true;                                     // codebook_size fields from 0.6 on
  RansLayout rans_layout = RansLayout::kInterleaved;         // of codebooks and the octree
  bool octree_positions = true;       // positions as octree_positions() from 0.7 on, else in Draco
  bool adaptive_attributes = true;    // attribute_coding and adaptive_attributes() from 0.8 on
  bool sh_dc_channel_context = true;  // SH DC channels on the previous channel from 0.11 on
};

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_GAUSSIAN_SET_SYNTAX_H_
