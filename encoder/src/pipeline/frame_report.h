// FrameReport: what the encoder measured for one coded frame: its bytes per packet type (the
// stream's bytes, headers included), Gaussian counts, held-out quality of the decoder's
// reconstruction, and time per stage.
#ifndef M4D_ENCODER_PIPELINE_FRAME_REPORT_H_
#define M4D_ENCODER_PIPELINE_FRAME_REPORT_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/stream/stream_writer.h"

namespace m4d {

struct StageSeconds {
  double keyframe = 0;      // keyframe training or retraining
  double decoupling = 0;    // lookahead fine-tuning and classification
  double motion = 0;        // motion estimation
  double compensation = 0;  // candidates and their training
  double coding = 0;        // writing packets and decoding them (closed loop)
  double evaluation = 0;    // held-out rendering
  double total() const {
    return keyframe + decoupling + motion + compensation + coding + evaluation;
  }
};

struct FrameReport {
  uint32_t frame_index = 0;
  bool keyframe = false;
  bool random_access = false;  // a keyframe with its SEQUENCE_HEADER and static layer
  PacketBytes bytes;           // by packet type
  size_t static_count = 0;     // Gaussians of the decoded frame
  size_t dynamic_count = 0;
  size_t added = 0;  // compensated Gaussians coded
  size_t removed = 0;
  double ratio = 0;  // r_t of the adaptive GOP (inter frames)
  // Mean PSNR over the training views of the coded frame (dB), what the adaptive GOP watches.
  double training_psnr = 0;
  // Training views' PSNR with the trained compensation minus without it (dB; inter frames
  // with compensation candidates). Below EncoderOptions::compensation_min_gain, none is coded.
  double compensation_gain = 0;
  // The compensation's training ended early: it was on course to stay under
  // EncoderOptions::compensation_min_gain (compensation_gain is then the probe's).
  bool compensation_abandoned = false;
  // Training views' PSNR of the moved dynamic set minus the unmoved one (dB; inter frames with
  // motion estimation). Not above EncoderOptions::motion_min_gain: the frame codes no motion
  // (motion_skipped).
  double motion_gain = 0;
  bool motion_skipped = false;
  // Training views' PSNR of the moved set with its colour change minus without it (dB; inter
  // frames whose motion trained one). Not above EncoderOptions::appearance_min_gain: no
  // APPEARANCE is coded (appearance_skipped).
  double appearance_gain = 0;
  bool appearance_skipped = true;
  // What the adaptive GOP's quality guard compares training_psnr with (dB, inter frames): the
  // keyframe's training PSNR less its noise gap (noise_gap.h).
  double psnr_reference = 0;
  // A keyframe that restarted a GOP after its frame was predicted: that prediction's
  // training_psnr (dB), what the retraining started from and has to beat (0: none).
  double prediction_psnr = 0;
  // Such a keyframe: Gaussians seeded where that prediction was unexplained
  // (retraining_growth.h).
  size_t seeded = 0;
  bool held_out = false;  // psnr and ssim were measured: the capture has a held-out camera
  double psnr = 0;        // held-out camera, decoded frame (dB)
  double ssim = 0;
  std::string hash;  // frame hash (bitstream-spec 7) of the encoder's reconstruction
  StageSeconds seconds;
};

struct SequenceReport {
  std::vector<FrameReport> frames;
  size_t stream_bytes = 0;  // the whole stream
  // The encoding process's peak resident memory (0: not measured; chunked: rank 0's).
  size_t peak_memory_bytes = 0;
};

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_FRAME_REPORT_H_
