// SequenceEncoder: the reference encoder over a sequence (paper sections 3 to 5), closed loop.
//
// Per GOP: the keyframe model (trained from the capture's points for the first GOP, retrained
// from the previous frame's decoded state for later ones) is decoupled into static and dynamic
// sets by the lookahead. Per inter frame t: motion estimation moves frame t-1's *decoded*
// dynamic set; compensation adds and removes Gaussians; mode decisions keep each of the colour
// change, the motion and the compensation only where it pays (appearance_decision.h,
// motion_decision.h, compensation_decision.h); the GOP policy (gop_policy.h) either codes the
// frame or starts a new GOP at t (when r_t exceeds tau_GOP, or when the frame's quality over the
// training views has fallen too far below the keyframe's). Every packet is decoded by the SDK as
// it is written and the next frame starts from that decode.
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
#include "encoder/src/motion/motion_estimation.h"
#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/pipeline/frame_report.h"
#include "encoder/src/pipeline/gop_policy.h"
#include "encoder/src/pipeline/held_out_evaluation.h"
#include "encoder/src/pipeline/retraining_growth.h"
#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/progress_bar.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

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
  HeldOutViewCallback held_out_view;
};

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
  struct InterFrame;
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
  Status WriteKeyframe();
  // Codes `frame` in the GOP, or sets *restart (nothing of the frame written) when the GOP
  // policy starts a new GOP at it.
  Status EncodeInterFrame(int frame, bool* restart);
  // The decoder's moved set of the frame: motion estimation, then the appearance and motion
  // decisions.
  Status Move(InterFrame* f);
  Status EstimateMotion(InterFrame* f);
  Status DecideMotionModes(InterFrame* f);
  // The gain the frame's colour change must exceed (RequiredAppearanceGain).
  Status RequiredGain(const InterFrame& f, double* required) const;
  // The frame's compensation: trained, then the compensation decision.
  Status Compensate(InterFrame* f);
  Status TrainFrameCompensation(InterFrame* f);
  Status WriteInterFrame(InterFrame* f);
  // Evaluates the GOP's decoded state as `frame` and reports it.
  Status ReportFrame(int frame, FrameReport* report);
  Status Restart(int frame);
  // The new GOP's keyframe model, retrained from the GOP's state predicted to `frame`.
  Status Retrain(int frame, bool dependent, GaussianModel* model, RetrainingGrowth* growth);

  const Capture& capture_;
  EncoderOptions options_;
  EncoderCallbacks callbacks_;
  SequenceReport* report_ = nullptr;
  GopPolicy gop_policy_;
  int last_frame_ = 0;
  std::unique_ptr<StreamWriter> writer_;
  std::unique_ptr<MotionEstimator> estimator_;
  std::unique_ptr<Gop> gop_;
  std::unique_ptr<GaussianModel> first_keyframe_;
  KeyframeSource keyframe_source_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_SEQUENCE_ENCODER_H_
