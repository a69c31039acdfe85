// SEQUENCE_HEADER payload (bitstream-spec 4.1): version, SH degree, frame rate, and the
// configuration of the motion grid and the shared MLP. It opens every GOP.
#ifndef M4D_SDK_BITSTREAM_SEQUENCE_HEADER_H_
#define M4D_SDK_BITSTREAM_SEQUENCE_HEADER_H_

#include <cstdint>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/gaussian_set_syntax.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

// The oldest bitstream minor version this decoder implements (0.2 is 0.3 without dependent
// keyframes, 0.3 is 0.4 without interleaved rANS states, 0.4 is 0.5 without smallest-three
// rotations, 0.5 is 0.6 without codebooks, 0.6 is 0.7 with positions in Draco, 0.7 is 0.8
// without adaptive attributes, 0.8 is 0.9 without up_axis, 0.9 is 0.10 with brick-coded grids,
// 0.10 is 0.11 with SH DC conditioned on the neighbour; spec 10).
constexpr int kOldestBitstreamMinor = 2;

// up_axis (spec 4.1): 0 not stated, 1..6 the world's up is +x, -x, +y, -y, +z, -z.
constexpr int kMaxUpAxis = 6;

// True when the version is one this decoder implements.
inline bool SupportedBitstreamVersion(int major, int minor) {
  return major == M4D_BITSTREAM_VERSION_MAJOR && minor >= kOldestBitstreamMinor &&
         minor <= M4D_BITSTREAM_VERSION_MINOR;
}

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
  int up_axis = 0;  // M4dUpAxis; always 0 before 0.9

  // Dependent keyframes and STATIC_UPDATE exist from 0.3 on.
  bool allows_dependent_gops() const { return version_minor >= 3; }
  bool allows_appearance() const { return version_minor >= 3; }
  // The up_axis field ends the payload from 0.9 on.
  bool allows_up_axis() const { return version_minor >= 9; }
  // MOTION_GRID codes the values of the voxels the dynamic set reads from 0.10 on, before it
  // brick flags and the values of flagged bricks (spec 4.4).
  bool codes_active_voxels() const { return version_minor >= 10; }
  // Interleaved rANS states exist from 0.4 on.
  RansLayout rans_layout() const {
    return version_minor >= 4 ? RansLayout::kInterleaved : RansLayout::kSingleState;
  }
  // Smallest-three rotations exist from 0.5 on, codebooks from 0.6 on, octree positions from
  // 0.7 on, adaptive attributes from 0.8 on.
  GaussianSetSyntax gaussian_set_syntax() const {
    GaussianSetSyntax syntax;
    syntax.rotation =
        version_minor >= 5 ? RotationCoding::kSmallestThree : RotationCoding::kFourComponents;
    syntax.codebooks = version_minor >= 6;
    syntax.octree_positions = version_minor >= 7;
    syntax.adaptive_attributes = version_minor >= 8;
    syntax.sh_dc_channel_context = version_minor >= 11;
    syntax.rans_layout = rans_layout();
    return syntax;
  }
};

// Reads and validates a SEQUENCE_HEADER payload (the whole payload must be consumed).
// Grids above `max_grid_values` fail with M4D_ERR_LIMIT.
Status ReadSequenceHeader(ByteReader* reader, uint32_t max_grid_values, SequenceHeader* out);

// Checks the ranges of every field (shared by the reader and the encoder's writer).
Status ValidateSequenceHeader(const SequenceHeader& header, uint32_t max_grid_values);

}  // namespace m4d

#endif  // M4D_SDK_BITSTREAM_SEQUENCE_HEADER_H_
