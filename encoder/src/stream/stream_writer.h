// StreamWriter: turns in-memory keyframe sets, MLP weights, motion grids and compensation
// into packets, and decodes every packet it writes with the SDK's own Decoder, so the encoder
// continues from exactly what any conforming decoder reconstructs (closed loop).
#ifndef M4D_ENCODER_STREAM_STREAM_WRITER_H_
#define M4D_ENCODER_STREAM_STREAM_WRITER_H_

#include <array>
#include <cstdint>
#include <vector>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/layers/motion_grid_writer.h"
#include "sdk/src/bitstream/sequence_header.h"
#include "sdk/src/decode/decoder.h"
#include "sdk/src/layers/mlp_weights.h"

namespace m4d {

struct StreamWriterOptions {
  SequenceHeader sequence;
  GaussianQuantization quantization;               // keyframe layers
  GaussianQuantization compensation_quantization;  // compensated Gaussians of inter frames
  int mlp_bits = 12;
  uint32_t first_frame_index = 0;  // frame_index of the first frame written
};

// A change of a set (COMPENSATION, STATIC_UPDATE): one flag per Gaussian of the set (non-zero
// = remove) and the Gaussians added (spec 6.4 places them).
struct SetChange {
  std::vector<uint8_t> removed;
  GaussianSet added;
};

// Bytes written per packet type (index = M4dPacketType), packet headers included.
struct PacketBytes {
  std::array<size_t, 9> by_type{};
  size_t total() const {
    size_t t = 0;
    for (size_t b : by_type) t += b;
    return t;
  }
};

class StreamWriter {
 public:
  explicit StreamWriter(const StreamWriterOptions& options);

  // Starts a GOP: SEQUENCE_HEADER, KEYFRAME_STATIC, KEYFRAME_DYNAMIC, MLP_WEIGHTS. The sets'
  // sh_degree must be the sequence's. *recon receives the decoded keyframe.
  Status WriteKeyframe(const GaussianSet& static_set, const GaussianSet& dynamic_set,
                       const MlpWeights& mlp, DecodedFrame* recon);

  // Starts a dependent GOP (bitstream 0.3): the previous frame's static set stays, changed by
  // `static_change` (a STATIC_UPDATE, written only when it removes or adds a Gaussian; its
  // flags refer to static_set()), then KEYFRAME_DYNAMIC and MLP_WEIGHTS. Needs a finished
  // frame before it.
  Status WriteDependentKeyframe(const SetChange& static_change, const GaussianSet& dynamic_set,
                                const MlpWeights& mlp, DecodedFrame* recon);
  // The decoder's static set after the last packet written.
  const GaussianSet& static_set() const { return *decoder_.static_set(); }

  // First packet of an inter frame. Afterwards moved_dynamic_set() is the decoder's dynamic
  // set after this motion, which the compensation refers to.
  Status WriteMotion(const FloatMotionGrid& grid);
  const GaussianSet& moved_dynamic_set() const { return *decoder_.dynamic_set(); }
  // The payload WriteMotion writes for a dynamic set `read_by` before the packet, for decisions
  // that weigh an inter frame's bytes before its GOP's keyframe is written.
  Status MotionPayload(const FloatMotionGrid& grid, const GaussianSet& read_by,
                       std::vector<uint8_t>* payload) const;

  // Optional packet after the motion (bitstream 0.3): the colour change of the moved dynamic
  // set, `values` 3 per Gaussian of moved_dynamic_set(), which it changes.
  Status WriteAppearance(float step, const std::vector<int32_t>& values);
  // The payload WriteAppearance would write.
  Status AppearancePayload(float step, const std::vector<int32_t>& values,
                           std::vector<uint8_t>* payload) const;

  // Last packet of an inter frame: `removed` holds one flag per Gaussian of
  // moved_dynamic_set() (non-zero = remove), `added` the compensated Gaussians.
  Status WriteCompensation(const std::vector<uint8_t>& removed, const GaussianSet& added,
                           DecodedFrame* recon);

  const std::vector<uint8_t>& bytes() const { return bytes_; }
  // Bytes of the last complete frame, by packet type.
  const PacketBytes& last_frame_bytes() const { return last_frame_; }
  uint32_t next_frame_index() const { return next_frame_; }

 private:
  Status Emit(uint8_t type, bool end_of_frame, const std::vector<uint8_t>& payload);
  Status TakeReconstruction(DecodedFrame* recon);
  // num_removed, the flags when any, the added set (spec 4.5).
  Status WriteSetChange(const std::vector<uint8_t>& removed, const GaussianSet& added,
                        const GaussianQuantization& quantization, std::vector<uint8_t>* payload);
  GaussianQuantization ForStream(const GaussianQuantization& quantization) const;
  Status WriteDynamicAndMlp(const GaussianSet& dynamic_set, const MlpWeights& mlp,
                            DecodedFrame* recon);

  StreamWriterOptions options_;
  Decoder decoder_;
  std::vector<uint8_t> bytes_;
  PacketBytes current_;
  PacketBytes last_frame_;
  uint32_t next_frame_ = 0;
  bool gop_open_ = false;
  bool motion_written_ = false;
  bool appearance_written_ = false;
};

}  // namespace m4d

#endif  // M4D_ENCODER_STREAM_STREAM_WRITER_H_
