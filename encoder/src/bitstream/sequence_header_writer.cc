#include "encoder/src/bitstream/sequence_header_writer.h"

#include "sdk/src/common/spec_limits.h"

namespace m4d {

Status WriteSequenceHeader(const SequenceHeader& h, ByteWriter* out) {
  M4D_RETURN_IF_ERROR(ValidateSequenceHeader(h, kMaxGridValues));
  out->WriteU8(static_cast<uint8_t>(h.version_major));
  out->WriteU8(static_cast<uint8_t>(h.version_minor));
  out->WriteU8(static_cast<uint8_t>(h.profile));
  out->WriteU8(static_cast<uint8_t>(h.sh_degree));
  out->WriteU32(h.fps_num);
  out->WriteU32(h.fps_den);
  out->WriteU32(h.num_frames);
  out->WriteU8(static_cast<uint8_t>(h.grid.num_levels));
  for (int l = 0; l < h.grid.num_levels; ++l)
    out->WriteU8(static_cast<uint8_t>(h.grid.channels[l]));
  for (int l = 0; l < h.grid.num_levels; ++l) {
    out->WriteU16(static_cast<uint16_t>(h.grid.resolution[l]));
  }
  out->WriteU8(static_cast<uint8_t>(h.mlp.hidden_layers));
  out->WriteU16(static_cast<uint16_t>(h.mlp.hidden_width));
  if (h.allows_up_axis()) out->WriteU8(static_cast<uint8_t>(h.up_axis));
  return Status::Ok();
}

}  // namespace m4d
