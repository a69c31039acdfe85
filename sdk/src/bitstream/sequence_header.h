// SEQUENCE_HEADER payload (bitstream-spec 4.1): version, SH degree, frame rate, and the
// configuration of the motion grid and the shared MLP. It opens every GOP.
#ifndef M4D_BITSTREAM_SEQUENCE_HEADER_H_
#define M4D_BITSTREAM_SEQUENCE_HEADER_H_

#include <cstdint>

#include "common/byte_reader.h"
#include "common/status.h"
#include "layers/motion_config.h"

namespace m4d {

struct SequenceHeader {
  int version_major = M4D_BITSTREAM_VERSION_MAJOR;
  int version_minor = M4D_BITSTREAM_VERSION_MINOR;
  int profile = 0;
  int sh_degree = 0;
  uint32_t fps_num = 30;
  uint32_t fps_den = 1;
  uint32_t num_frames = 0;
  GridConfig grid;
  MlpConfig mlp;
};

// Reads and validates a SEQUENCE_HEADER payload (the whole payload must be consumed).
// Grids above `max_grid_values` fail with M4D_ERR_LIMIT.
Status ReadSequenceHeader(ByteReader* reader, uint32_t max_grid_values, SequenceHeader* out);

// Checks the ranges of every field (shared by the reader and the encoder's writer).
Status ValidateSequenceHeader(const SequenceHeader& header, uint32_t max_grid_values);

}  // namespace m4d

#endif  // M4D_BITSTREAM_SEQUENCE_HEADER_H_
