// Decoder: the decoding process of bitstream-spec section 6 as a packet-driven state machine.
// The C API (api/m4d_api.cc) wraps it; the encoder drives one directly to reconstruct exactly
// what every decoder will output (closed loop).
#ifndef M4D_SDK_DECODE_DECODER_H_
#define M4D_SDK_DECODE_DECODER_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "sdk/src/bitstream/packet_header.h"
#include "sdk/src/bitstream/sequence_header.h"
#include "sdk/src/common/status.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {

struct DecoderOptions {
  uint32_t layers = M4D_LAYER_ALL;
  uint32_t max_gaussians = 0;    // 0: the spec's limit
  uint32_t max_grid_values = 0;  // 0: the spec's limit
  bool verify_checksums = true;
  int threads = 1;                          // 0: every core (M4dSettings.threads)
  const M4dAllocator* allocator = nullptr;  // must outlive the decoder
  std::function<void(int level, const std::string& message)> log;
};

// One output frame. The sets are immutable and shared between frames (the static layer by
// every frame of a GOP); an absent layer is an empty set.
struct DecodedFrame {
  uint32_t frame_index = 0;
  bool is_keyframe = false;
  uint32_t layers = 0;
  uint32_t concealed = 0;  // layers lost to damage (spec 6.8): content not the stream's
  std::shared_ptr<const GaussianSet> static_layer;
  std::shared_ptr<const GaussianSet> dynamic_layer;
};

// What the decoder has seen of the stream since it was made (a flush keeps it): the last
// configuration and the GOP structure (M4dStreamInfo).
struct StreamStats {
  bool configured = false;    // a SEQUENCE_HEADER was decoded
  SequenceHeader sequence;    // the last one decoded
  bool static_coded = false;  // the current random-access GOP has a KEYFRAME_STATIC
  uint32_t frames = 0;        // frames taken (TakeFrame)
  uint32_t gops = 0;
  uint32_t random_access_gops = 0;
  uint32_t last_keyframe = 0;
  uint32_t last_random_access = 0;
};

class Decoder {
 public:
  explicit Decoder(const DecoderOptions& options);

  // Decodes one whole packet (header + payload, `size` bytes exactly). The caller must have
  // taken the previous frame first (HasFrame() false). A damaged payload of a layer's packet
  // loses that layer only (spec 6.8): the packet's frame may still be output, concealed. On
  // any other error the decoder drops its state and skips packets until the next
  // SEQUENCE_HEADER.
  Status SendPacket(const uint8_t* data, size_t size);

  bool HasFrame() const { return has_frame_; }
  DecodedFrame TakeFrame();

  // Drops all state and any pending frame; keeps the options and the caller background.
  void Flush();

  // Replaces the static layer of every following frame (nullptr restores the stream's).
  void SetBackground(std::shared_ptr<const GaussianSet> background);

  // The dynamic set after the last decoded packet: after a MOTION_GRID, the moved set the
  // following COMPENSATION edits (the encoder decides its compensation from it).
  const GaussianSet* dynamic_set() const { return dynamic_.get(); }
  // The static set S of the stream (a dependent keyframe's STATIC_UPDATE refers to it).
  const GaussianSet* static_set() const { return static_.get(); }
  const SequenceHeader& sequence_header() const { return sequence_; }
  const StreamStats& stream_stats() const { return stats_; }

 private:
  enum class Stage {
    kNeedSequenceHeader,
    kKeyframeStart,
    kKeyframeStatic,
    kKeyframeDynamic,
    kInter,
    kMotion,
    kAppearance
  };

  Status Dispatch(const PacketHeader& header, const uint8_t* payload, bool* layer_error);
  Status CheckOrder(const PacketHeader& header);
  bool ChecksPayload(uint8_t type) const;
  bool DecodesPayload(uint8_t type) const;
  Status DecodeLayerPayload(const PacketHeader& header, const uint8_t* payload);
  void LoseLayer(uint8_t type);
  void Advance(const PacketHeader& header);
  Status DecodeSequenceHeader(const PacketHeader& header, const uint8_t* payload);
  Status DecodeKeyframeSet(const uint8_t* payload, size_t size, bool is_static);
  Status DecodeStaticUpdate(const uint8_t* payload, size_t size);
  Status DecodeMlp(const uint8_t* payload, size_t size);
  Status DecodeMotion(const uint8_t* payload, size_t size);
  Status DecodeAppearance(const uint8_t* payload, size_t size);
  Status DecodeCompensation(const uint8_t* payload, size_t size);
  // The syntax shared by COMPENSATION and STATIC_UPDATE (spec 4.5, 4.6) over a set of n.
  Status ReadSetChange(const uint8_t* payload, size_t size, const char* what, uint32_t n,
                       Buffer<int32_t>* removed, uint32_t* num_removed, GaussianSet* added);
  Status CheckDependentKeyframe(const PacketHeader& header) const;
  void EmitFrame(uint32_t frame_index, bool is_keyframe);
  std::shared_ptr<const GaussianSet> OutputStaticLayer() const;
  void CountKeyframe(uint32_t frame_index);
  void Reset();
  GaussianSet* MutableDynamicSet();
  GaussianSet* MutableStaticSet();
  uint32_t MaxGaussians() const;
  bool wants(uint32_t layer) const { return (options_.layers & layer) != 0; }

  DecoderOptions options_;
  Stage stage_ = Stage::kNeedSequenceHeader;
  uint32_t frame_index_ = 0;  // frame being decoded
  SequenceHeader sequence_;
  std::shared_ptr<GaussianSet> static_;  // shared with output frames; copied on write
  // False once a static packet was skipped for a caller background: the stream's S is then
  // unknown (empty) until the next SEQUENCE_HEADER (spec 6.6).
  bool static_known_ = true;
  // Layers lost to a damaged payload (spec 6.8): S until the next SEQUENCE_HEADER, D until the
  // next KEYFRAME_DYNAMIC that decodes; a lost MLP loses D at the GOP's next frame.
  bool static_lost_ = false;
  bool dynamic_lost_ = false;
  bool mlp_lost_ = false;
  // The layers of the last frame output: what a lost layer shows meanwhile (informative).
  std::shared_ptr<const GaussianSet> last_static_out_;
  std::shared_ptr<const GaussianSet> last_dynamic_out_;
  std::shared_ptr<GaussianSet> dynamic_;  // shared with output frames; copied on write
  std::shared_ptr<const GaussianSet> background_;
  MlpWeights mlp_;
  MotionGrid grid_;
  bool has_frame_ = false;
  DecodedFrame frame_;
  bool gop_random_access_ = false;  // the GOP being decoded started with a SEQUENCE_HEADER
  StreamStats stats_;
  std::unique_ptr<ThreadPool> pool_;  // none when decoding on the caller's thread only
};

}  // namespace m4d

#endif  // M4D_SDK_DECODE_DECODER_H_
