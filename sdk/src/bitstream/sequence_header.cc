#include "sdk/src/bitstream/sequence_header.h"

#include <string>

namespace m4d {

Status ValidateSequenceHeader(const SequenceHeader& h, uint32_t max_grid_values) {
  if (!SupportedBitstreamVersion(h.version_major, h.version_minor)) {
    return Status(M4D_ERR_UNSUPPORTED, "sequence header: bitstream version " +
                                           std::to_string(h.version_major) + "." +
                                           std::to_string(h.version_minor) + " not supported");
  }
  if (h.profile != 0) return Status(M4D_ERR_UNSUPPORTED, "sequence header: unknown profile");
  if (h.sh_degree < 0 || h.sh_degree > 3) return BitstreamError("sequence header: sh_degree > 3");
  const uint32_t kMaxRate = 1u << 31;
  if (h.fps_num == 0 || h.fps_den == 0 || h.fps_num > kMaxRate || h.fps_den > kMaxRate) {
    return BitstreamError("sequence header: frame rate out of range");
  }
  const GridConfig& g = h.grid;
  if (g.num_levels < 1 || g.num_levels > kMaxGridLevels) {
    return BitstreamError("sequence header: grid levels out of range 1..4");
  }
  for (int l = 0; l < g.num_levels; ++l) {
    if (g.channels[l] < 1 || g.channels[l] > kMaxGridChannels) {
      return BitstreamError("sequence header: grid channels out of range 1..8");
    }
    if (g.resolution[l] < 2 || g.resolution[l] > kMaxGridResolution) {
      return BitstreamError("sequence header: grid resolution out of range 2..256");
    }
  }
  if (g.total_values() > kMaxGridValues) {
    return LimitError("sequence header: grid of " + std::to_string(g.total_values()) +
                      " values above the limit of 2^24");
  }
  if (g.total_values() > max_grid_values) {
    return LimitError("sequence header: grid of " + std::to_string(g.total_values()) +
                      " values above the decoder's limit");
  }
  if (h.mlp.hidden_layers < 1 || h.mlp.hidden_layers > kMaxMlpHiddenLayers) {
    return BitstreamError("sequence header: MLP hidden layers out of range 1..4");
  }
  if (h.mlp.hidden_width < 1 || h.mlp.hidden_width > kMaxMlpWidth) {
    return BitstreamError("sequence header: MLP width out of range 1..256");
  }
  if (h.up_axis < 0 || h.up_axis > kMaxUpAxis) {
    return BitstreamError("sequence header: up_axis " + std::to_string(h.up_axis) +
                          " out of range 0..6");
  }
  if (h.up_axis != 0 && !h.allows_up_axis()) {
    return BitstreamError("sequence header: up_axis needs version 0.9");
  }
  return Status::Ok();
}

Status ReadSequenceHeader(ByteReader* reader, uint32_t max_grid_values, SequenceHeader* out) {
  uint8_t major, minor, profile, sh_degree, levels;
  if (!reader->ReadU8(&major) || !reader->ReadU8(&minor) || !reader->ReadU8(&profile)) {
    return BitstreamError("sequence header: truncated");
  }
  SequenceHeader h;
  h.version_major = major;
  h.version_minor = minor;
  h.profile = profile;
  // Versions are checked first so that a newer stream reports "unsupported", not garbage.
  if (!SupportedBitstreamVersion(major, minor) || profile != 0) {
    return ValidateSequenceHeader(h, max_grid_values);
  }
  if (!reader->ReadU8(&sh_degree) || !reader->ReadU32(&h.fps_num) || !reader->ReadU32(&h.fps_den) ||
      !reader->ReadU32(&h.num_frames) || !reader->ReadU8(&levels)) {
    return BitstreamError("sequence header: truncated");
  }
  h.sh_degree = sh_degree;
  h.grid.num_levels = levels;
  if (levels < 1 || levels > kMaxGridLevels) {
    return BitstreamError("sequence header: grid levels out of range 1..4");
  }
  for (int l = 0; l < kMaxGridLevels; ++l) h.grid.channels[l] = h.grid.resolution[l] = 0;
  for (int l = 0; l < levels; ++l) {
    uint8_t c;
    if (!reader->ReadU8(&c)) return BitstreamError("sequence header: truncated");
    h.grid.channels[l] = c;
  }
  for (int l = 0; l < levels; ++l) {
    uint16_t r;
    if (!reader->ReadU16(&r)) return BitstreamError("sequence header: truncated");
    h.grid.resolution[l] = r;
  }
  uint8_t hidden_layers;
  uint16_t width;
  if (!reader->ReadU8(&hidden_layers) || !reader->ReadU16(&width)) {
    return BitstreamError("sequence header: truncated");
  }
  h.mlp.hidden_layers = hidden_layers;
  h.mlp.hidden_width = width;
  if (h.allows_up_axis()) {
    uint8_t up_axis;
    if (!reader->ReadU8(&up_axis)) return BitstreamError("sequence header: truncated");
    h.up_axis = up_axis;
  }
  M4D_RETURN_IF_ERROR(ValidateSequenceHeader(h, max_grid_values));
  *out = h;
  return Status::Ok();
}

}  // namespace m4d
