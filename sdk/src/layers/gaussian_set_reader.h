// Decoding of gaussian_set() (bitstream-spec 5.4, 5.5): quantization parameters, then a Draco
// point cloud of integer attributes, dequantized with the spec's formula.
#ifndef M4D_SDK_LAYERS_GAUSSIAN_SET_READER_H_
#define M4D_SDK_LAYERS_GAUSSIAN_SET_READER_H_

#include <cstdint>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/adaptive_attributes.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_set_syntax.h"

namespace m4d {

// Attribute groups of a Gaussian set, in coding order (spec 5.4).
enum GaussianGroup {
  kGroupPosition,
  kGroupLogScale,
  kGroupRotation,
  kGroupOpacity,
  kGroupShDc,
  kGroupShRest,
  kNumGaussianGroups
};

// Number of components of a group for the given SH degree (0 for sh_rest at degree 0).
int GaussianGroupComponents(int group, int sh_degree);

// Number of components a group codes with (min, step): 3 for smallest-three rotations, whose
// index is a Draco attribute of its own (spec 5.4, 5.5).
int CodedGroupComponents(int group, int sh_degree, RotationCoding rotation);

// Whether a group may be coded with a codebook (version 0.6, spec 5.4): log scales, SH DC and
// higher SH.
bool GroupAllowsCodebook(int group);

// What adaptive_attributes() (version 0.8, spec 5.7) conditions a group's values on: scalar log
// scales and rotations also on the Gaussian's previous component, so does SH DC (from 0.11 on
// that component alone); codebook indices and the rotation index on the neighbour's only.
AdaptiveContext AdaptiveContextOf(int group, bool codebook, bool rotation_index,
                                  const GaussianSetSyntax& syntax);

// Reads one gaussian_set() from `reader`, with the stream version's syntax. `out` must
// have been constructed (with the caller's allocator); its sh_degree is set to `sh_degree` and
// it is resized to the decoded count. Counts above `max_count` fail with M4D_ERR_LIMIT before
// any allocation.
Status ReadGaussianSet(ByteReader* reader, int sh_degree, const GaussianSetSyntax& syntax,
                       uint32_t max_count, GaussianSet* out);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_GAUSSIAN_SET_READER_H_
