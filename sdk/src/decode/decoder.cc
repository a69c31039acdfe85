#include "sdk/src/decode/decoder.h"

#include <string>
#include <utility>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/crc32.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/decode/appearance_application.h"
#include "sdk/src/decode/compensation_merge.h"
#include "sdk/src/decode/motion_application.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/appearance_update.h"
#include "sdk/src/layers/gaussian_set_reader.h"

namespace m4d {
namespace {

const char* PacketName(uint8_t type) {
  switch (type) {
    case M4D_PACKET_SEQUENCE_HEADER:
      return "SEQUENCE_HEADER";
    case M4D_PACKET_KEYFRAME_STATIC:
      return "KEYFRAME_STATIC";
    case M4D_PACKET_KEYFRAME_DYNAMIC:
      return "KEYFRAME_DYNAMIC";
    case M4D_PACKET_MLP_WEIGHTS:
      return "MLP_WEIGHTS";
    case M4D_PACKET_MOTION_GRID:
      return "MOTION_GRID";
    case M4D_PACKET_COMPENSATION:
      return "COMPENSATION";
    case M4D_PACKET_STATIC_UPDATE:
      return "STATIC_UPDATE";
    case M4D_PACKET_APPEARANCE:
      return "APPEARANCE";
    default:
      return "unknown";
  }
}

Status RequireConsumed(const ByteReader& reader, const char* what) {
  if (reader.remaining() != 0) {
    return BitstreamError(std::string(what) + ": " + std::to_string(reader.remaining()) +
                          " bytes left after the payload's syntax");
  }
  return Status::Ok();
}

}  // namespace

Decoder::Decoder(const DecoderOptions& options) : options_(options), grid_(options.allocator) {
  if (options.threads != 1) pool_ = std::make_unique<ThreadPool>(options.threads);
}

uint32_t Decoder::MaxGaussians() const {
  return (options_.max_gaussians == 0 || options_.max_gaussians > kMaxGaussiansPerSet)
             ? kMaxGaussiansPerSet
             : options_.max_gaussians;
}

void Decoder::Reset() {
  stage_ = Stage::kNeedSequenceHeader;
  static_.reset();
  dynamic_.reset();
  mlp_ = MlpWeights();
}

void Decoder::Flush() {
  Reset();
  has_frame_ = false;
  frame_ = DecodedFrame();
  last_static_out_.reset();
  last_dynamic_out_.reset();
}

void Decoder::SetBackground(std::shared_ptr<const GaussianSet> background) {
  background_ = std::move(background);
}

DecodedFrame Decoder::TakeFrame() {
  has_frame_ = false;
  ++stats_.frames;
  return std::exchange(frame_, DecodedFrame());
}

Status Decoder::SendPacket(const uint8_t* data, size_t size) {
  PacketHeader header;
  Status status = ParsePacketHeader(data, size, &header);
  if (status.code() == M4D_ERR_AGAIN) status = BitstreamError("packet shorter than its header");
  if (status.ok() && size - kPacketHeaderSize != header.payload_size) {
    status = BitstreamError("packet of " + std::to_string(size) + " bytes declares a payload of " +
                            std::to_string(header.payload_size) + " bytes");
  }
  // A SEQUENCE_HEADER inside a frame (spec 9): the incomplete frame is dropped and reported,
  // and the header still starts the next GOP, so decoding goes on without a packet lost.
  const bool cuts_frame = status.ok() && header.type == M4D_PACKET_SEQUENCE_HEADER &&
                          stage_ != Stage::kNeedSequenceHeader && stage_ != Stage::kInter;
  const uint32_t cut_frame = frame_index_;
  bool layer_error = false;
  if (status.ok()) status = Dispatch(header, data + kPacketHeaderSize, &layer_error);
  if (!status.ok()) {
    if (!layer_error) Reset();
    return status;
  }
  if (cuts_frame) {
    return BitstreamError("SEQUENCE_HEADER inside frame " + std::to_string(cut_frame) +
                          ": that frame is dropped, decoding goes on from this header");
  }
  return status;
}

Status Decoder::CheckOrder(const PacketHeader& h) {
  const char* name = PacketName(h.type);
  auto order_error = [&](const std::string& why) {
    return BitstreamError(std::string(name) + " (frame " + std::to_string(h.frame_index) +
                          "): " + why);
  };
  const bool last_of_frame = h.type == M4D_PACKET_MLP_WEIGHTS || h.type == M4D_PACKET_COMPENSATION;
  if (h.end_of_frame() != last_of_frame) return order_error("wrong end_of_frame flag");
  switch (h.type) {
    case M4D_PACKET_KEYFRAME_STATIC:
      if (stage_ != Stage::kKeyframeStart) return order_error("not after a SEQUENCE_HEADER");
      break;
    case M4D_PACKET_STATIC_UPDATE:
      if (stage_ != Stage::kInter) return order_error("not after a complete frame");
      return CheckDependentKeyframe(h);
    case M4D_PACKET_KEYFRAME_DYNAMIC:
      if (stage_ == Stage::kInter) return CheckDependentKeyframe(h);
      if (stage_ != Stage::kKeyframeStart && stage_ != Stage::kKeyframeStatic) {
        return order_error(
            "not after a SEQUENCE_HEADER, KEYFRAME_STATIC, STATIC_UPDATE or "
            "a complete frame");
      }
      break;
    case M4D_PACKET_MLP_WEIGHTS:
      if (stage_ != Stage::kKeyframeDynamic) return order_error("not after KEYFRAME_DYNAMIC");
      break;
    case M4D_PACKET_MOTION_GRID:
      if (stage_ != Stage::kInter) return order_error("not after a complete frame");
      if (h.frame_index != frame_index_ + 1) return order_error("frame index not consecutive");
      return Status::Ok();
    case M4D_PACKET_APPEARANCE:
      if (!sequence_.allows_appearance()) {
        return order_error("an appearance update in a version 0." +
                           std::to_string(sequence_.version_minor) + " stream");
      }
      if (stage_ != Stage::kMotion) return order_error("not after MOTION_GRID");
      break;
    case M4D_PACKET_COMPENSATION:
      if (stage_ != Stage::kMotion && stage_ != Stage::kAppearance) {
        return order_error("not after MOTION_GRID or APPEARANCE");
      }
      break;
    default:
      return Status(M4D_ERR_UNSUPPORTED, "unknown packet type " + std::to_string(h.type));
  }
  if (h.frame_index != frame_index_) return order_error("frame index differs within a frame");
  return Status::Ok();
}

// A dependent keyframe (spec 2, 6.5) follows a complete frame, with the next frame index, in a
// stream of version 0.3 or later.
Status Decoder::CheckDependentKeyframe(const PacketHeader& h) const {
  const std::string where =
      std::string(PacketName(h.type)) + " (frame " + std::to_string(h.frame_index) + "): ";
  if (!sequence_.allows_dependent_gops()) {
    return BitstreamError(where + "a dependent keyframe in a version 0." +
                          std::to_string(sequence_.version_minor) + " stream");
  }
  if (h.frame_index != frame_index_ + 1) {
    return BitstreamError(where + "frame index not consecutive");
  }
  return Status::Ok();
}

Status Decoder::Dispatch(const PacketHeader& h, const uint8_t* payload, bool* layer_error) {
  if (h.type < M4D_PACKET_SEQUENCE_HEADER || h.type > M4D_PACKET_APPEARANCE) {
    return Status(M4D_ERR_UNSUPPORTED, "unknown packet type " + std::to_string(h.type));
  }
  if (h.type != M4D_PACKET_SEQUENCE_HEADER && stage_ == Stage::kNeedSequenceHeader) {
    // No configuration yet (stream start, flush or error): skip until the next GOP (spec 6.1).
    if (options_.log) {
      options_.log(M4D_LOG_INFO, std::string("skipping ") + PacketName(h.type) + " of frame " +
                                     std::to_string(h.frame_index) + " until a SEQUENCE_HEADER");
    }
    return Status::Ok();
  }
  if (h.type == M4D_PACKET_SEQUENCE_HEADER) {
    // Its end_of_frame is a packet-order check (E8), made before it is decoded and before a
    // frame it cuts is reported (E12): rejected, it drops the state as any order error.
    if (h.end_of_frame()) {
      return BitstreamError("SEQUENCE_HEADER (frame " + std::to_string(h.frame_index) +
                            "): wrong end_of_frame flag");
    }
    return DecodeSequenceHeader(h, payload);
  }
  M4D_RETURN_IF_ERROR(CheckOrder(h));
  const bool is_static = h.type == M4D_PACKET_KEYFRAME_STATIC || h.type == M4D_PACKET_STATIC_UPDATE;
  if (is_static && background_) static_known_ = false;
  // A damaged payload loses its layer, not the frame (spec 6.8): the packet still takes its
  // place in the GOP, so the frame it ends is output with that layer concealed.
  Status status = Status::Ok();
  if (ChecksPayload(h.type)) status = DecodeLayerPayload(h, payload);
  if (!status.ok()) {
    if (status.code() == M4D_ERR_NOMEM) return status;
    *layer_error = true;
    LoseLayer(h.type);
  }
  Advance(h);
  return status;
}

// Whether a payload is read (its CRC checked): only for an output layer the decoder still
// holds (spec 6.6, 6.8); a lost dynamic layer is restored by the next KEYFRAME_DYNAMIC.
bool Decoder::ChecksPayload(uint8_t type) const {
  switch (type) {
    case M4D_PACKET_KEYFRAME_STATIC:
    case M4D_PACKET_STATIC_UPDATE:
      return wants(M4D_LAYER_STATIC) && !background_ && !static_lost_;
    case M4D_PACKET_KEYFRAME_DYNAMIC:
      return wants(M4D_LAYER_DYNAMIC);
    case M4D_PACKET_MLP_WEIGHTS:
      return wants(M4D_LAYER_DYNAMIC) && !dynamic_lost_;
    default:
      return wants(M4D_LAYER_DYNAMIC) && !dynamic_lost_ && !mlp_lost_;
  }
}

// A STATIC_UPDATE's CRC is checked but it is not applied once a caller background made S
// unknown (spec 6.6).
bool Decoder::DecodesPayload(uint8_t type) const {
  return type != M4D_PACKET_STATIC_UPDATE || static_known_;
}

Status Decoder::DecodeLayerPayload(const PacketHeader& h, const uint8_t* payload) {
  if (options_.verify_checksums && Crc32(payload, h.payload_size) != h.payload_crc) {
    return Status(M4D_ERR_CHECKSUM, std::string(PacketName(h.type)) + " (frame " +
                                        std::to_string(h.frame_index) + "): payload CRC mismatch");
  }
  if (!DecodesPayload(h.type)) return Status::Ok();
  const size_t size = h.payload_size;
  switch (h.type) {
    case M4D_PACKET_KEYFRAME_STATIC:
      return DecodeKeyframeSet(payload, size, true);
    case M4D_PACKET_STATIC_UPDATE:
      return DecodeStaticUpdate(payload, size);
    case M4D_PACKET_KEYFRAME_DYNAMIC:
      return DecodeKeyframeSet(payload, size, false);
    case M4D_PACKET_MLP_WEIGHTS:
      return DecodeMlp(payload, size);
    case M4D_PACKET_MOTION_GRID:
      return DecodeMotion(payload, size);
    case M4D_PACKET_APPEARANCE:
      return DecodeAppearance(payload, size);
    default:  // M4D_PACKET_COMPENSATION (CheckOrder rejected every other type)
      return DecodeCompensation(payload, size);
  }
}

void Decoder::LoseLayer(uint8_t type) {
  const bool is_static = type == M4D_PACKET_KEYFRAME_STATIC || type == M4D_PACKET_STATIC_UPDATE;
  if (is_static) {
    static_lost_ = true;
  } else if (type == M4D_PACKET_MLP_WEIGHTS) {
    mlp_lost_ = true;  // the keyframe's own D is intact; the GOP's next frames are not
  } else {
    dynamic_lost_ = true;
  }
  if (options_.log) {
    options_.log(M4D_LOG_WARNING,
                 is_static ? "static layer lost: concealed until the next SEQUENCE_HEADER"
                           : "dynamic layer lost: concealed until the next KEYFRAME_DYNAMIC");
  }
}

// The packet order's state after a packet, decoded, skipped or lost alike.
void Decoder::Advance(const PacketHeader& h) {
  switch (h.type) {
    case M4D_PACKET_KEYFRAME_STATIC:
      stats_.static_coded = true;
      stage_ = Stage::kKeyframeStatic;
      return;
    case M4D_PACKET_STATIC_UPDATE:
      gop_random_access_ = false;
      frame_index_ = h.frame_index;
      stage_ = Stage::kKeyframeStatic;
      return;
    case M4D_PACKET_KEYFRAME_DYNAMIC:
      if (stage_ == Stage::kInter) gop_random_access_ = false;  // a dependent keyframe
      frame_index_ = h.frame_index;
      stage_ = Stage::kKeyframeDynamic;
      return;
    case M4D_PACKET_MLP_WEIGHTS:
      stage_ = Stage::kInter;
      CountKeyframe(h.frame_index);
      EmitFrame(h.frame_index, true);
      return;
    case M4D_PACKET_MOTION_GRID:
      if (mlp_lost_) dynamic_lost_ = true;
      frame_index_ = h.frame_index;
      stage_ = Stage::kMotion;
      return;
    case M4D_PACKET_APPEARANCE:
      stage_ = Stage::kAppearance;
      return;
    default:  // M4D_PACKET_COMPENSATION
      stage_ = Stage::kInter;
      EmitFrame(h.frame_index, false);
      return;
  }
}

Status Decoder::DecodeSequenceHeader(const PacketHeader& h, const uint8_t* payload) {
  Reset();
  if (options_.verify_checksums && Crc32(payload, h.payload_size) != h.payload_crc) {
    return Status(M4D_ERR_CHECKSUM, "SEQUENCE_HEADER: payload CRC mismatch");
  }
  ByteReader reader(payload, h.payload_size);
  const uint32_t max_grid =
      options_.max_grid_values == 0 ? kMaxGridValues : options_.max_grid_values;
  M4D_RETURN_IF_ERROR(ReadSequenceHeader(&reader, max_grid, &sequence_));
  M4D_RETURN_IF_ERROR(RequireConsumed(reader, "SEQUENCE_HEADER"));
  auto empty_static = std::make_shared<GaussianSet>(options_.allocator);
  empty_static->sh_degree = sequence_.sh_degree;
  static_ = std::move(empty_static);  // stays empty in foreground-only streams
  static_known_ = true;
  static_lost_ = dynamic_lost_ = mlp_lost_ = false;
  dynamic_ = std::make_shared<GaussianSet>(options_.allocator);
  dynamic_->sh_degree = sequence_.sh_degree;
  frame_index_ = h.frame_index;
  stage_ = Stage::kKeyframeStart;
  gop_random_access_ = true;
  stats_.configured = true;
  stats_.sequence = sequence_;
  stats_.static_coded = false;
  return Status::Ok();
}

void Decoder::CountKeyframe(uint32_t frame_index) {
  ++stats_.gops;
  stats_.last_keyframe = frame_index;
  if (gop_random_access_) {
    ++stats_.random_access_gops;
    stats_.last_random_access = frame_index;
  }
}

Status Decoder::DecodeKeyframeSet(const uint8_t* payload, size_t size, bool is_static) {
  auto set = std::make_shared<GaussianSet>(options_.allocator);
  ByteReader reader(payload, size);
  const char* what = is_static ? "KEYFRAME_STATIC" : "KEYFRAME_DYNAMIC";
  Status status = ReadGaussianSet(&reader, sequence_.sh_degree, sequence_.gaussian_set_syntax(),
                                  MaxGaussians(), set.get());
  if (!status.ok()) return Status(status.code(), std::string(what) + ": " + status.message());
  M4D_RETURN_IF_ERROR(RequireConsumed(reader, what));
  if (is_static) {
    static_ = std::move(set);
  } else {
    dynamic_ = std::move(set);
    dynamic_lost_ = mlp_lost_ = false;  // a new D restores a lost dynamic layer
  }
  return Status::Ok();
}

Status Decoder::DecodeMlp(const uint8_t* payload, size_t size) {
  ByteReader reader(payload, size);
  Status status = ReadMlpWeights(&reader, sequence_.rans_layout(), sequence_.grid.feature_count(),
                                 sequence_.mlp, &mlp_);
  if (!status.ok()) return Status(status.code(), "MLP_WEIGHTS: " + status.message());
  M4D_RETURN_IF_ERROR(RequireConsumed(reader, "MLP_WEIGHTS"));
  mlp_lost_ = false;
  return Status::Ok();
}

GaussianSet* Decoder::MutableDynamicSet() {
  // Frames handed out share the set; copy it only while a caller still holds one.
  if (dynamic_.use_count() > 1) dynamic_ = std::make_shared<GaussianSet>(*dynamic_);
  return dynamic_.get();
}

GaussianSet* Decoder::MutableStaticSet() {
  if (static_.use_count() > 1) static_ = std::make_shared<GaussianSet>(*static_);
  return static_.get();
}

Status Decoder::DecodeMotion(const uint8_t* payload, size_t size) {
  ByteReader reader(payload, size);
  const Status status =
      sequence_.codes_active_voxels()
          ? ReadActiveMotionGrid(&reader, sequence_.rans_layout(), sequence_.grid,
                                 dynamic_->positions.data(), dynamic_->size(), &grid_)
          : ReadMotionGrid(&reader, sequence_.rans_layout(), sequence_.grid, &grid_);
  if (!status.ok()) return Status(status.code(), "MOTION_GRID: " + status.message());
  M4D_RETURN_IF_ERROR(RequireConsumed(reader, "MOTION_GRID"));
  ApplyMotion(sequence_.grid, grid_, mlp_, MutableDynamicSet(), pool_.get());
  return Status::Ok();
}

Status Decoder::DecodeAppearance(const uint8_t* payload, size_t size) {
  ByteReader reader(payload, size);
  AppearanceUpdate update(options_.allocator);
  Status status = ReadAppearanceUpdate(&reader, sequence_.rans_layout(),
                                       static_cast<uint32_t>(dynamic_->size()), &update);
  if (!status.ok()) return Status(status.code(), "APPEARANCE: " + status.message());
  M4D_RETURN_IF_ERROR(RequireConsumed(reader, "APPEARANCE"));
  ApplyAppearanceUpdate(update, MutableDynamicSet());
  return Status::Ok();
}

Status Decoder::ReadSetChange(const uint8_t* payload, size_t size, const char* what, uint32_t n,
                              Buffer<int32_t>* removed, uint32_t* num_removed, GaussianSet* added) {
  const std::string prefix = std::string(what) + ": ";
  ByteReader reader(payload, size);
  if (!reader.ReadVarUint(num_removed)) return BitstreamError(prefix + "truncated");
  if (*num_removed > n) return BitstreamError(prefix + "removes more Gaussians than exist");
  if (*num_removed > 0) {
    removed->resize(n);
    Status status = ReadSymbolBlock(&reader, sequence_.rans_layout(), n, 0, 1, removed->data());
    if (!status.ok()) return Status(status.code(), prefix + status.message());
    uint32_t ones = 0;
    for (int32_t flag : *removed) ones += static_cast<uint32_t>(flag);
    if (ones != *num_removed) return BitstreamError(prefix + "removal count mismatch");
  }
  const uint32_t max = MaxGaussians();
  Status status =
      ReadGaussianSet(&reader, sequence_.sh_degree, sequence_.gaussian_set_syntax(), max, added);
  if (!status.ok()) return Status(status.code(), prefix + status.message());
  M4D_RETURN_IF_ERROR(RequireConsumed(reader, what));
  if (static_cast<uint64_t>(n - *num_removed) + added->size() > max) {
    return LimitError(prefix + "the set would exceed " + std::to_string(max));
  }
  return Status::Ok();
}

Status Decoder::DecodeCompensation(const uint8_t* payload, size_t size) {
  Buffer<int32_t> removed{HookedAllocator<int32_t>(options_.allocator)};
  uint32_t num_removed = 0;
  GaussianSet added(options_.allocator);
  M4D_RETURN_IF_ERROR(ReadSetChange(payload, size, "COMPENSATION",
                                    static_cast<uint32_t>(dynamic_->size()), &removed, &num_removed,
                                    &added));
  MergeCompensation(num_removed > 0 ? removed.data() : nullptr, added, MutableDynamicSet());
  return Status::Ok();
}

Status Decoder::DecodeStaticUpdate(const uint8_t* payload, size_t size) {
  Buffer<int32_t> removed{HookedAllocator<int32_t>(options_.allocator)};
  uint32_t num_removed = 0;
  GaussianSet added(options_.allocator);
  M4D_RETURN_IF_ERROR(ReadSetChange(payload, size, "STATIC_UPDATE",
                                    static_cast<uint32_t>(static_->size()), &removed, &num_removed,
                                    &added));
  MergeCompensation(num_removed > 0 ? removed.data() : nullptr, added, MutableStaticSet());
  return Status::Ok();
}

void Decoder::EmitFrame(uint32_t frame_index, bool is_keyframe) {
  frame_ = DecodedFrame();
  frame_.frame_index = frame_index;
  frame_.is_keyframe = is_keyframe;
  frame_index_ = frame_index;
  auto empty = std::make_shared<const GaussianSet>();
  if (wants(M4D_LAYER_STATIC)) {
    frame_.layers |= M4D_LAYER_STATIC;
    frame_.static_layer = OutputStaticLayer();
    if (!background_ && static_lost_) frame_.concealed |= M4D_LAYER_STATIC;
  } else {
    frame_.static_layer = empty;
  }
  if (wants(M4D_LAYER_DYNAMIC)) {
    frame_.layers |= M4D_LAYER_DYNAMIC;
    frame_.dynamic_layer = dynamic_;
    if (dynamic_lost_) {
      frame_.concealed |= M4D_LAYER_DYNAMIC;
      if (last_dynamic_out_) frame_.dynamic_layer = last_dynamic_out_;  // frozen
    }
  } else {
    frame_.dynamic_layer = empty;
  }
  last_static_out_ = frame_.static_layer;
  last_dynamic_out_ = frame_.dynamic_layer;
  has_frame_ = true;
}

// The static layer a frame shows: the caller's, the stream's, or while the stream's is lost
// the last one output (the previous GOP's; informative, spec 6.8).
std::shared_ptr<const GaussianSet> Decoder::OutputStaticLayer() const {
  if (background_) return background_;
  if (static_lost_ && last_static_out_) return last_static_out_;
  if (static_known_ && !static_lost_) return static_;
  auto unknown = std::make_shared<GaussianSet>();
  unknown->sh_degree = sequence_.sh_degree;
  return unknown;
}

}  // namespace m4d
