// SequenceEncoder: the reference encoder over a sequence (paper sections 3 to 5), closed loop.
//
// Per GOP: the keyframe model (trained from the capture's points for the first GOP, retrained
// from the previous frame's decoded state for later ones) is decoupled into static and dynamic
// sets by the lookahead. Per inter frame t: motion estimation moves frame t-1's *decoded*
// dynamic set; compensation adds and removes Gaussians; the adaptive GOP rule either codes
// the frame or starts a new GOP at t (when r_t exceeds tau_GOP, or when the frame's quality
// over the training views has fallen too far below the keyframe's). Every packet is decoded by the
// SDK as it is written and the next frame starts from that decode.
//
// The keyframe's packets carry the GOP's shared MLP, which the first inter frame trains, so a
// keyframe is written just before its first inter frame. An inter frame is decided before any
// of its packets is written: its moved set is computed with the SDK's own motion code on the
// quantized grid and MLP, exactly what the decoder will compute (checked when written).
#ifndef M4D_ENCODER_PIPELINE_SEQUENCE_ENCODER_H_
#define M4D_ENCODER_PIPELINE_SEQUENCE_ENCODER_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/image/image.h"
#include "encoder/src/motion/motion_estimation.h"
#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/pipeline/frame_report.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/progress_bar.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/appearance_update.h"

namespace m4d {

struct EncoderCallbacks {
  // Progress of a keyframe (re)training; stage is "keyframe" or "retrain".
  std::function<void(const std::string& stage, int frame, const TrainingProgress&)> training;
  // A frame was coded (keyframes are reported when written, just before their first inter
  // frame).
  std::function<void(const FrameReport&)> frame_coded;
  // A stage began: "decoupling", "motion", "compensation".
  std::function<void(const std::string& stage, int frame)> stage;
  // The held-out camera's image of a coded frame and the render of its decoded Gaussians
  // (clamped to [0, 1]); only called when the capture has a held-out camera.
  std::function<void(int frame, const Image& truth, const Image& render)> held_out_view;
};

// The training of a keyframe from scratch: options.keyframe with the stream's SH degree,
// quantization, background, threads and seed.
KeyframeTrainingOptions FirstKeyframeTraining(const EncoderOptions& options);

class SequenceEncoder {
 public:
  SequenceEncoder(const Capture& capture, const EncoderOptions& options);
  ~SequenceEncoder();

  // Starts the first GOP from this model (e.g. a keyframe trained earlier, read from a PLY)
  // instead of training one; its SH degree must be at least the stream's.
  void SetFirstKeyframe(GaussianModel model);

  // Frame -> a model trained on it earlier. With EncoderOptions::independent_frames, every
  // frame's model comes from here instead of being trained (so that several rate points of
  // the baseline share one training per frame).
  using KeyframeSource = std::function<Status(int frame, GaussianModel* model)>;
  void SetKeyframeSource(KeyframeSource source);

  Status Encode(const EncoderCallbacks& callbacks, SequenceReport* report);

  // The stream written so far.
  const std::vector<uint8_t>& stream() const;

 private:
  struct Gop;
  // A keyframe trained from the capture's points (or taken from the caller).
  Status ScratchKeyframe(int frame, GaussianModel* model);
  Status EncodeIndependentFrames();
  // A random-access GOP: the model is decoupled into static and dynamic sets.
  Status StartGop(int frame, GaussianModel model, double keyframe_seconds);
  // A dependent GOP: static_set stays; the model's other Gaussians are the dynamic set.
  Status StartDependentGop(int frame, GaussianModel model, GaussianSet static_set,
                           double keyframe_seconds);
  Status OpenGop(int frame, double keyframe_seconds, bool dependent, TrainingViews* views);
  // Per Gaussian of a new GOP's model, 1 for the dynamic layer (the lookahead decoupling; all 1
  // without decoupling, all 0 when no frame follows).
  Status DynamicFlags(int frame, const GaussianModel& model, const TrainingViews& views,
                      std::vector<uint8_t>* dynamic);
  Status FinishGopStart(int frame, const TrainingViews& views);
  // Whether a GOP starting at `frame` keeps the static set (GopOptions::random_access_seconds).
  bool DependentGop(int frame) const;
  Status EncodeInterFrame(int frame, bool* restart);
  Status WriteKeyframe();
  Status Restart(int frame);
  // The keyframe schedule shortened to options_.retrain_iterations for a restart at `frame`.
  KeyframeTrainingOptions RetrainingOptions(int frame, bool dependent) const;
  Status Evaluate(int frame, const GaussianSet& static_set, const GaussianSet& dynamic_set,
                  FrameReport* report);
  // The keyframe's overfit to its own frame's noise, in dB: its PSNR over the pixels that did
  // not change between the GOP's first two frames (temporal_change.h), on its own frame's
  // training views minus on `next` (the second frame's). A keyframe that fitted sensor noise
  // loses that much on the next frame where nothing moved, so the quality guard compares inter
  // frames with the keyframe's PSNR less this gap, not with what no inter frame can reach.
  // 0 on a noise-free capture.
  Status NoiseGap(const TrainingViews& next, double* gap);
  // Mode decision (ours): the frame moves its dynamic set only if that raises the training views'
  // mean PSNR by more than options_.motion_min_gain above showing the previous frame again. On real
  // captures the motion of an over-dynamic keyframe can make a frame worse than doing nothing (a
  // classroom capture: docs/results/2026-11-30-comment-measurements.md); a skipped frame's grid is
  // SkipMotion's.
  Status DecideMotion(const GaussianSet& still, const GaussianSet& moved, bool* skip,
                      FrameReport* report);
  // Applies the frame's colour change to *moved when it raises the training views' PSNR by
  // more than options_.appearance_min_gain (sets report's appearance gain and skip flag).
  Status DecideAppearance(const AppearanceUpdate& appearance, GaussianSet* moved,
                          FrameReport* report);
  // Training views' PSNR of kept (moved without the removed Gaussians) with added, minus
  // moved's: the probe of compensation's early decision.
  Status CompensationGain(const GaussianSet& moved, const GaussianSet& kept,
                          const GaussianSet& added, double* gain);
  // Sets report's training PSNR and compensation gain; drops the compensation (nothing added
  // or removed) when it gains less than options_.compensation_min_gain.
  Status DecideCompensation(const GaussianSet& moved, CompensationResult* compensation,
                            FrameReport* report);
  // Mean PSNR over the frame's training views of the GOP's static set with dynamic_set (the
  // adaptive GOP's quality measure; TrainingPsnrMeter).
  Status TrainingPsnr(const GaussianSet& dynamic_set, double* psnr);
  RenderSettings Settings() const;

  const Capture& capture_;
  EncoderOptions options_;
  EncoderCallbacks callbacks_;
  SequenceReport* report_ = nullptr;
  int last_frame_ = 0;
  int random_access_start_ = 0;  // first frame of the last random-access GOP
  std::unique_ptr<StreamWriter> writer_;
  std::unique_ptr<MotionEstimator> estimator_;
  std::unique_ptr<Gop> gop_;
  std::unique_ptr<GaussianModel> first_keyframe_;
  KeyframeSource keyframe_source_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_SEQUENCE_ENCODER_H_
