#include "encoder/src/stream/stream_writer.h"

#include <string>

#include "encoder/src/bitstream/sequence_header_writer.h"
#include "encoder/src/entropy/symbol_block_writer.h"
#include "encoder/src/layers/appearance_update_writer.h"
#include "encoder/src/layers/mlp_weights_writer.h"
#include "sdk/src/bitstream/packet_header.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/spec_limits.h"

namespace m4d {
namespace {

DecoderOptions ClosedLoopOptions() {
  DecoderOptions options;
  options.layers = M4D_LAYER_ALL;
  return options;
}

}  // namespace

StreamWriter::StreamWriter(const StreamWriterOptions& options)
    : options_(options), decoder_(ClosedLoopOptions()), next_frame_(options.first_frame_index) {}

// Sets are coded with the gaussian_set() syntax of the sequence's version, whatever the options
// say: the encoder's reconstructions come from decoding what is written.
GaussianQuantization StreamWriter::ForStream(const GaussianQuantization& quantization) const {
  GaussianQuantization coded = quantization;
  coded.syntax = options_.sequence.gaussian_set_syntax();
  return coded;
}

Status StreamWriter::Emit(uint8_t type, bool end_of_frame, const std::vector<uint8_t>& payload) {
  if (payload.size() > kMaxPayloadSize) {
    return LimitError("packet payload of " + std::to_string(payload.size()) + " bytes");
  }
  const size_t start = bytes_.size();
  AppendPacket(type, next_frame_, end_of_frame, payload.data(), payload.size(), &bytes_);
  current_.by_type[type] += bytes_.size() - start;
  // Closed loop: the SDK decodes what was just written.
  return decoder_.SendPacket(bytes_.data() + start, bytes_.size() - start);
}

Status StreamWriter::TakeReconstruction(DecodedFrame* recon) {
  if (!decoder_.HasFrame()) return Status(M4D_ERR_BITSTREAM, "writer: frame not completed");
  DecodedFrame frame = decoder_.TakeFrame();
  if (recon) *recon = std::move(frame);
  last_frame_ = current_;
  current_ = PacketBytes();
  ++next_frame_;
  return Status::Ok();
}

Status StreamWriter::WriteKeyframe(const GaussianSet& static_set, const GaussianSet& dynamic_set,
                                   const MlpWeights& mlp, DecodedFrame* recon) {
  const int sh = options_.sequence.sh_degree;
  if (static_set.sh_degree != sh || dynamic_set.sh_degree != sh) {
    return Status(M4D_ERR_INVALID_ARG, "writer: set SH degree differs from the sequence's");
  }
  if (motion_written_) return Status(M4D_ERR_INVALID_ARG, "writer: inter frame not finished");
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  M4D_RETURN_IF_ERROR(WriteSequenceHeader(options_.sequence, &writer));
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_SEQUENCE_HEADER, false, payload));

  payload.clear();
  M4D_RETURN_IF_ERROR(WriteGaussianSet(static_set, ForStream(options_.quantization), &writer));
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_KEYFRAME_STATIC, false, payload));

  return WriteDynamicAndMlp(dynamic_set, mlp, recon);
}

Status StreamWriter::WriteDynamicAndMlp(const GaussianSet& dynamic_set, const MlpWeights& mlp,
                                        DecodedFrame* recon) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  M4D_RETURN_IF_ERROR(WriteGaussianSet(dynamic_set, ForStream(options_.quantization), &writer));
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_KEYFRAME_DYNAMIC, false, payload));

  payload.clear();
  M4D_RETURN_IF_ERROR(
      WriteMlpWeights(mlp, options_.mlp_bits, options_.sequence.rans_layout(), &writer));
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_MLP_WEIGHTS, true, payload));
  gop_open_ = true;
  return TakeReconstruction(recon);
}

Status StreamWriter::WriteDependentKeyframe(const SetChange& static_change,
                                            const GaussianSet& dynamic_set, const MlpWeights& mlp,
                                            DecodedFrame* recon) {
  const int sh = options_.sequence.sh_degree;
  if (static_change.added.sh_degree != sh || dynamic_set.sh_degree != sh) {
    return Status(M4D_ERR_INVALID_ARG, "writer: set SH degree differs from the sequence's");
  }
  if (!gop_open_ || motion_written_) {
    return Status(M4D_ERR_INVALID_ARG, "writer: a dependent keyframe needs a finished frame");
  }
  if (options_.sequence.version_minor < 3) {
    return Status(M4D_ERR_INVALID_ARG, "writer: dependent keyframes need bitstream 0.3");
  }
  if (static_change.removed.size() != static_set().size()) {
    return Status(M4D_ERR_INVALID_ARG, "writer: removal flags do not match the static set");
  }
  bool removes = false;
  for (uint8_t flag : static_change.removed) removes = removes || flag != 0;
  if (removes || static_change.added.size() > 0) {
    std::vector<uint8_t> payload;
    M4D_RETURN_IF_ERROR(WriteSetChange(static_change.removed, static_change.added,
                                       options_.quantization, &payload));
    M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_STATIC_UPDATE, false, payload));
  }
  return WriteDynamicAndMlp(dynamic_set, mlp, recon);
}

Status StreamWriter::WriteMotion(const FloatMotionGrid& grid) {
  if (!gop_open_ || motion_written_) {
    return Status(M4D_ERR_INVALID_ARG, "writer: motion needs an open GOP and a finished frame");
  }
  std::vector<uint8_t> payload;
  M4D_RETURN_IF_ERROR(MotionPayload(grid, moved_dynamic_set(), &payload));  // frame t-1's
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_MOTION_GRID, false, payload));
  motion_written_ = true;
  return Status::Ok();
}

Status StreamWriter::MotionPayload(const FloatMotionGrid& grid, const GaussianSet& read_by,
                                   std::vector<uint8_t>* payload) const {
  payload->clear();
  ByteWriter writer(payload);
  const SequenceHeader& sequence = options_.sequence;
  return sequence.codes_active_voxels()
             ? WriteActiveMotionGrid(sequence.grid, grid, read_by.positions.data(), read_by.size(),
                                     sequence.rans_layout(), &writer)
             : WriteMotionGrid(sequence.grid, grid, sequence.rans_layout(), &writer);
}

Status StreamWriter::WriteAppearance(float step, const std::vector<int32_t>& values) {
  if (!motion_written_ || appearance_written_) {
    return Status(M4D_ERR_INVALID_ARG, "writer: appearance needs motion and no appearance yet");
  }
  if (values.size() != 3 * moved_dynamic_set().size()) {
    return Status(M4D_ERR_INVALID_ARG, "writer: appearance values do not match the dynamic set");
  }
  std::vector<uint8_t> payload;
  M4D_RETURN_IF_ERROR(AppearancePayload(step, values, &payload));
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_APPEARANCE, false, payload));
  appearance_written_ = true;
  return Status::Ok();
}

Status StreamWriter::AppearancePayload(float step, const std::vector<int32_t>& values,
                                       std::vector<uint8_t>* payload) const {
  payload->clear();
  ByteWriter writer(payload);
  return WriteAppearanceUpdate(step, values, options_.sequence.rans_layout(), &writer);
}

Status StreamWriter::WriteCompensation(const std::vector<uint8_t>& removed,
                                       const GaussianSet& added, DecodedFrame* recon) {
  if (!motion_written_) return Status(M4D_ERR_INVALID_ARG, "writer: compensation before motion");
  if (removed.size() != moved_dynamic_set().size()) {
    return Status(M4D_ERR_INVALID_ARG, "writer: removal flags do not match the dynamic set");
  }
  if (added.sh_degree != options_.sequence.sh_degree) {
    return Status(M4D_ERR_INVALID_ARG, "writer: set SH degree differs from the sequence's");
  }
  std::vector<uint8_t> payload;
  M4D_RETURN_IF_ERROR(WriteSetChange(removed, added, options_.compensation_quantization, &payload));
  M4D_RETURN_IF_ERROR(Emit(M4D_PACKET_COMPENSATION, true, payload));
  motion_written_ = false;
  appearance_written_ = false;
  return TakeReconstruction(recon);
}

Status StreamWriter::WriteSetChange(const std::vector<uint8_t>& removed, const GaussianSet& added,
                                    const GaussianQuantization& quantization,
                                    std::vector<uint8_t>* payload) {
  std::vector<int32_t> flags(removed.size());
  uint32_t num_removed = 0;
  for (size_t i = 0; i < removed.size(); ++i) {
    flags[i] = removed[i] ? 1 : 0;
    num_removed += static_cast<uint32_t>(flags[i]);
  }
  ByteWriter writer(payload);
  writer.WriteVarUint(num_removed);
  if (num_removed > 0)
    M4D_RETURN_IF_ERROR(
        WriteSymbolBlock(flags.data(), flags.size(), options_.sequence.rans_layout(), &writer));
  return WriteGaussianSet(added, ForStream(quantization), &writer);
}

}  // namespace m4d
