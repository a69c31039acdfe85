// Merging of a frame's compensated Gaussians into the dynamic set (bitstream-spec 6.4).
// Added Gaussians fill the removed slots first, so the cost is proportional to the number of
// removed and added Gaussians, not to the size of the set.
#ifndef M4D_SDK_DECODE_COMPENSATION_MERGE_H_
#define M4D_SDK_DECODE_COMPENSATION_MERGE_H_

#include <cstddef>
#include <cstdint>

#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// `removed` holds one flag (0 or 1) per Gaussian of `set`, or is null when none is removed;
// `added` has the same SH degree as `set`.
void MergeCompensation(const int32_t* removed, const GaussianSet& added, GaussianSet* set);

}  // namespace m4d

#endif  // M4D_SDK_DECODE_COMPENSATION_MERGE_H_
