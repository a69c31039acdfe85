// Stable LSD radix sort of (key, value) pairs by 32-bit key, 8 bits per pass; passes in
// which all keys share the digit are skipped. Used to order splats by depth: the bits of a
// positive float sort like the float.
#ifndef M4D_SDK_RENDER_RADIX_SORT_H_
#define M4D_SDK_RENDER_RADIX_SORT_H_

#include <cstdint>
#include <vector>

namespace m4d {

// Sorts keys ascending, permuting values alongside. The scratch vectors are resized as
// needed and may be reused between calls.
void RadixSortPairs(std::vector<uint32_t>* keys, std::vector<uint32_t>* values,
                    std::vector<uint32_t>* key_scratch, std::vector<uint32_t>* value_scratch);

}  // namespace m4d

#endif  // M4D_SDK_RENDER_RADIX_SORT_H_
