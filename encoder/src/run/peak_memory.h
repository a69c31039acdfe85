// The process's peak resident memory, which the encoder's report records: a long capture must
// not need more memory than a short one (frames are loaded when needed and dropped after).
#ifndef M4D_ENCODER_RUN_PEAK_MEMORY_H_
#define M4D_ENCODER_RUN_PEAK_MEMORY_H_

#include <cstddef>

namespace m4d {

// Peak resident set size of this process so far, in bytes (0 where the system does not say).
size_t PeakMemoryBytes();

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_PEAK_MEMORY_H_
