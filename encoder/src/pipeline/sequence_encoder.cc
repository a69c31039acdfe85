#include "encoder/src/pipeline/sequence_encoder.h"

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "encoder/src/compensation/compensation_candidates.h"
#include "encoder/src/compensation/compensation_training.h"
#include "encoder/src/decoupling/lookahead_decoupling.h"
#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/layers/motion_grid_writer.h"
#include "encoder/src/layers/same_gaussian_set.h"
#include "encoder/src/motion/appearance_estimation.h"
#include "encoder/src/pipeline/appearance_decision.h"
#include "encoder/src/pipeline/coded_motion.h"
#include "encoder/src/pipeline/combined_sets.h"
#include "encoder/src/pipeline/compensation_decision.h"
#include "encoder/src/pipeline/motion_decision.h"
#include "encoder/src/pipeline/noise_gap.h"
#include "encoder/src/pipeline/stage_options.h"
#include "encoder/src/pipeline/training_psnr_meter.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/scene_extent.h"
#include "sdk/src/decode/frame_hash.h"
#include "sdk/src/decode/motion_application.h"
#include "sdk/src/layers/appearance_update.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {

struct SequenceEncoder::Gop {
  int start = 0;
  bool keyframe_pending = true;
  bool dependent = false;          // keeps the previous GOP's static set (no SEQUENCE_HEADER)
  GaussianSet static_added_coded;  // a dependent GOP's additions to it, before quantization
  GaussianSet static_coded, dynamic_coded;  // the keyframe's sets before quantization
  GaussianSet static_set;                   // decoded, fixed for the GOP
  GaussianSet dynamic_set;                  // decoded, of the last coded frame
  // When a frame restarts the GOP: its dynamic set predicted from the last coded frame
  // (motion applied), where the retraining starts.
  GaussianSet predicted;
  double prediction_psnr = 0;  // its training PSNR (0: not measured)
  GridBox box;
  MlpWeights mlp;          // float, as trained (what the keyframe packet quantizes)
  MlpWeights decoded_mlp;  // as the decoder reads it back
  bool mlp_trained = false;
  float scene_extent = 1.0f;
  FrameReport keyframe_report;  // its training_psnr is what the adaptive GOP compares with
  // Of static_set, once it is decoded: its projection and render per training view, and the
  // mode decisions' PSNR.
  std::unique_ptr<FrozenLayerViews> static_views;
  std::unique_ptr<TrainingPsnrMeter> meter;
  double noise_gap = 0;  // noise_gap.h, measured at the first inter frame
};

// An inter frame on its way from its training views to its packets.
struct SequenceEncoder::InterFrame {
  int frame = 0;
  int length = 0;  // frames in the GOP before it
  TrainingViews views;
  bool motion_on = false;  // its motion is estimated
  MotionEstimationResult motion;
  FloatMotionGrid coded_grid;  // as written
  MotionGrid decoded_grid;     // as the decoder reads it
  AppearanceUpdate appearance;
  std::vector<int> appearance_check_views;  // the views that did not train it
  GaussianSet moved;                        // the decoder's moved dynamic set
  CompensationResult compensation;
  FrameReport report;
};

namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

SequenceEncoder::SequenceEncoder(const Capture& capture, const EncoderOptions& options)
    : capture_(capture), options_(options), gop_policy_(options) {}

SequenceEncoder::~SequenceEncoder() = default;

void SequenceEncoder::SetFirstKeyframe(GaussianModel model) {
  first_keyframe_ = std::make_unique<GaussianModel>(std::move(model));
}

void SequenceEncoder::SetKeyframeSource(KeyframeSource source) {
  keyframe_source_ = std::move(source);
}

const std::vector<uint8_t>& SequenceEncoder::stream() const {
  static const std::vector<uint8_t> kEmpty;
  return writer_ ? writer_->bytes() : kEmpty;
}

Status SequenceEncoder::Encode(const EncoderCallbacks& callbacks, SequenceReport* report) {
  M4D_RETURN_IF_ERROR(ValidateEncoderOptions(options_));
  const int first = options_.first_frame;
  if (first >= capture_.frame_count) {
    return Status(M4D_ERR_INVALID_ARG, "encoder: first frame beyond the capture");
  }
  const int frames = options_.frame_count > 0
                         ? std::min(options_.frame_count, capture_.frame_count - first)
                         : capture_.frame_count - first;
  last_frame_ = first + frames - 1;
  callbacks_ = callbacks;
  report_ = report;
  *report = SequenceReport();
  writer_ = std::make_unique<StreamWriter>(WriterOptions(options_, frames, capture_));
  estimator_ = std::make_unique<MotionEstimator>(options_.grid, options_.mlp, options_.grid_steps);

  if (options_.independent_frames) return EncodeIndependentFrames();
  const Clock::time_point start = Clock::now();
  GaussianModel model;
  M4D_RETURN_IF_ERROR(ScratchKeyframe(first, &model));
  M4D_RETURN_IF_ERROR(StartGop(first, std::move(model), Since(start)));
  for (int t = first + 1; t <= last_frame_; ++t) {
    bool restart = false;
    M4D_RETURN_IF_ERROR(EncodeInterFrame(t, &restart));
    if (restart) M4D_RETURN_IF_ERROR(Restart(t));
  }
  if (gop_->keyframe_pending) M4D_RETURN_IF_ERROR(WriteKeyframe());
  report->stream_bytes = writer_->bytes().size();
  return Status::Ok();
}

Status SequenceEncoder::ScratchKeyframe(int frame, GaussianModel* model) {
  if (keyframe_source_) {
    M4D_RETURN_IF_ERROR(keyframe_source_(frame, model));
  } else if (first_keyframe_ && frame == options_.first_frame) {
    *model = *first_keyframe_;
  } else {
    return TrainKeyframe(
        capture_, frame, FirstKeyframeTraining(options_),
        [&](const TrainingProgress& p) {
          if (callbacks_.training) callbacks_.training("keyframe", frame, p);
        },
        model);
  }
  if (model->sh_degree < options_.sh_degree) {
    return Status(M4D_ERR_INVALID_ARG, "encoder: keyframe's SH degree below the stream's");
  }
  return Status::Ok();
}

Status SequenceEncoder::EncodeIndependentFrames() {
  for (int t = options_.first_frame; t <= last_frame_; ++t) {
    const Clock::time_point start = Clock::now();
    GaussianModel model;
    M4D_RETURN_IF_ERROR(ScratchKeyframe(t, &model));
    M4D_RETURN_IF_ERROR(StartGop(t, std::move(model), Since(start)));
    M4D_RETURN_IF_ERROR(WriteKeyframe());
  }
  report_->stream_bytes = writer_->bytes().size();
  return Status::Ok();
}

Status SequenceEncoder::OpenGop(int frame, double keyframe_seconds, bool dependent,
                                TrainingViews* views) {
  gop_ = std::make_unique<Gop>();
  Gop& gop = *gop_;
  gop.start = frame;
  gop.dependent = dependent;
  gop.keyframe_report.frame_index = static_cast<uint32_t>(frame);
  gop.keyframe_report.keyframe = true;
  gop.keyframe_report.random_access = !dependent;
  gop.keyframe_report.seconds.keyframe = keyframe_seconds;
  gop_policy_.Started(frame, dependent);
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, frame, capture_.TrainCameras(), views));
  gop.scene_extent = CameraSceneBounds(views->cameras).extent;
  return Status::Ok();
}

Status SequenceEncoder::DynamicFlags(int frame, const GaussianModel& model,
                                     const TrainingViews& views, std::vector<uint8_t>* dynamic) {
  const int t1 = std::min(frame + options_.lookahead_frames, last_frame_);
  if (!options_.ablation.decoupling) {
    dynamic->assign(model.size(), 1);
    return Status::Ok();
  }
  if (t1 == frame || options_.independent_frames) {
    dynamic->assign(model.size(), 0);  // nothing follows: all of it is background
    return Status::Ok();
  }
  if (callbacks_.stage) callbacks_.stage("decoupling", frame);
  const Clock::time_point start = Clock::now();
  std::vector<TrainingViews> steps;
  for (int t = frame + options_.lookahead_step;; t += options_.lookahead_step) {
    t = std::min(t, t1);
    steps.emplace_back();
    M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, t, capture_.TrainCameras(), &steps.back()));
    if (t == t1) break;
  }
  DecouplingResult result;
  M4D_RETURN_IF_ERROR(DecoupleKeyframe(model, views, steps, gop_->scene_extent,
                                       KeyframeDecoupling(options_, frame), &result));
  *dynamic = std::move(result.dynamic);
  gop_->keyframe_report.seconds.decoupling = Since(start);
  return Status::Ok();
}

Status SequenceEncoder::StartGop(int frame, GaussianModel model, double keyframe_seconds) {
  TrainingViews views;
  M4D_RETURN_IF_ERROR(OpenGop(frame, keyframe_seconds, false, &views));
  Gop& gop = *gop_;
  std::vector<uint8_t> dynamic;
  M4D_RETURN_IF_ERROR(DynamicFlags(frame, model, views, &dynamic));
  GaussianModel static_model, dynamic_model;
  SplitModel(model, dynamic, &dynamic_model, &static_model);
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(static_model, options_.sh_degree, &gop.static_coded));
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(dynamic_model, options_.sh_degree, &gop.dynamic_coded));
  M4D_RETURN_IF_ERROR(
      ReconstructGaussianSet(gop.static_coded, options_.quantization, &gop.static_set));
  M4D_RETURN_IF_ERROR(
      ReconstructGaussianSet(gop.dynamic_coded, options_.quantization, &gop.dynamic_set));
  return FinishGopStart(frame, views);
}

Status SequenceEncoder::StartDependentGop(int frame, GaussianModel model, GaussianSet static_set,
                                          double keyframe_seconds) {
  TrainingViews views;
  M4D_RETURN_IF_ERROR(OpenGop(frame, keyframe_seconds, true, &views));
  Gop& gop = *gop_;
  // The model's first rows are the kept static set, unchanged by the retraining. The others (the
  // previous dynamic set, retrained, and what grew) are decoupled like a keyframe's: the dynamic
  // ones are the new dynamic layer, the static ones are added to the static set (a STATIC_UPDATE).
  // Left dynamic, what grew in the background widened the motion grid's box and drifted with it
  // (docs/results/2026-11-30-readme-notebook.md, "The static layer is sent once").
  std::vector<uint8_t> dynamic;
  M4D_RETURN_IF_ERROR(DynamicFlags(frame, model, views, &dynamic));
  std::vector<uint8_t> grown(model.size(), 1);
  std::fill(grown.begin(), grown.begin() + static_cast<std::ptrdiff_t>(static_set.size()), 0);
  model.Keep(grown);
  dynamic.erase(dynamic.begin(), dynamic.begin() + static_cast<std::ptrdiff_t>(static_set.size()));
  GaussianModel added_model, dynamic_model;
  SplitModel(model, dynamic, &dynamic_model, &added_model);
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(added_model, options_.sh_degree, &gop.static_added_coded));
  GaussianSet added;
  M4D_RETURN_IF_ERROR(
      ReconstructGaussianSet(gop.static_added_coded, options_.quantization, &added));
  gop.static_set = std::move(static_set);
  AppendKept(added, nullptr, &gop.static_set);  // 6.4 with nothing removed: an append
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(dynamic_model, options_.sh_degree, &gop.dynamic_coded));
  M4D_RETURN_IF_ERROR(
      ReconstructGaussianSet(gop.dynamic_coded, options_.quantization, &gop.dynamic_set));
  return FinishGopStart(frame, views);
}

Status SequenceEncoder::FinishGopStart(int frame, const TrainingViews& views) {
  Gop& gop = *gop_;
  const RenderSettings settings = EncoderRenderSettings(options_);
  gop.meter.reset();
  gop.static_views =
      std::make_unique<FrozenLayerViews>(GaussianView(gop.static_set), settings, views.size());
  gop.meter = std::make_unique<TrainingPsnrMeter>(gop.static_set, settings, gop.static_views.get());
  M4D_RETURN_IF_ERROR(gop.meter->StartFrame(views));
  M4D_RETURN_IF_ERROR(gop.meter->Measure(gop.dynamic_set, &gop.keyframe_report.training_psnr));
  gop.box = DynamicGridBox(gop.dynamic_set, 0.005f, 0.995f, 0.15f);
  estimator_->StartGop(options_.context.seed + static_cast<uint64_t>(frame));
  gop.mlp = estimator_->mlp();
  return DecodedMlp(gop.mlp, options_, &gop.decoded_mlp);
}

Status SequenceEncoder::WriteKeyframe() {
  Gop& gop = *gop_;
  const Clock::time_point start = Clock::now();
  DecodedFrame recon;
  if (gop.dependent) {
    SetChange change;  // nothing removed, what grew in the background added
    change.removed.assign(writer_->static_set().size(), 0);
    change.added = gop.static_added_coded;
    M4D_RETURN_IF_ERROR(
        writer_->WriteDependentKeyframe(change, gop.dynamic_coded, gop.mlp, &recon));
  } else {
    M4D_RETURN_IF_ERROR(
        writer_->WriteKeyframe(gop.static_coded, gop.dynamic_coded, gop.mlp, &recon));
  }
  if (!SameGaussianSet(*recon.static_layer, gop.static_set) ||
      !SameGaussianSet(*recon.dynamic_layer, gop.dynamic_set)) {
    return Status(M4D_ERR_BITSTREAM, "encoder: keyframe reconstruction differs from the decoder's");
  }
  gop.keyframe_pending = false;
  FrameReport& report = gop.keyframe_report;
  report.seconds.coding = Since(start);
  report.bytes = writer_->last_frame_bytes();
  report.hash = FrameHashHex(recon);
  return ReportFrame(gop.start, &report);
}

Status SequenceEncoder::EncodeInterFrame(int frame, bool* restart) {
  Gop& gop = *gop_;
  if (gop_policy_.EndsBefore(gop.start, frame)) {
    *restart = true;
    gop.predicted = gop.dynamic_set;  // no motion estimated: the last frame's
    gop.prediction_psnr = 0;
    return Status::Ok();
  }
  InterFrame f;
  f.frame = frame;
  f.length = frame - gop.start;
  f.report.frame_index = static_cast<uint32_t>(frame);
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, frame, capture_.TrainCameras(), &f.views));
  M4D_RETURN_IF_ERROR(gop.meter->StartFrame(f.views));
  Clock::time_point start = Clock::now();
  M4D_RETURN_IF_ERROR(Move(&f));
  f.report.seconds.motion = Since(start);
  start = Clock::now();
  M4D_RETURN_IF_ERROR(Compensate(&f));
  f.report.seconds.compensation = Since(start);
  if (options_.gop.noise_gap && f.length == 1) {
    M4D_RETURN_IF_ERROR(MeasureNoiseGap(capture_, gop.start, gop.static_set, gop.dynamic_set,
                                        f.views, options_.decoupling.change,
                                        EncoderRenderSettings(options_), &gop.noise_gap));
  }
  FrameReport& report = f.report;
  report.psnr_reference = gop.keyframe_report.training_psnr - gop.noise_gap;
  if (gop_policy_.Restarts(f.length, report.ratio, report.training_psnr, report.psnr_reference)) {
    *restart = true;  // frame becomes the next GOP's keyframe; nothing of it is written
    gop.predicted = std::move(f.moved);
    gop.prediction_psnr = report.training_psnr;
    return Status::Ok();
  }
  return WriteInterFrame(&f);
}

Status SequenceEncoder::Move(InterFrame* f) {
  Gop& gop = *gop_;
  f->motion_on = options_.ablation.motion_estimation && gop.dynamic_set.size() > 0;
  if (f->motion_on) M4D_RETURN_IF_ERROR(EstimateMotion(f));
  DenseGrids(options_.grid, options_.grid_steps, f->motion_on ? &f->motion : nullptr, gop.box,
             &f->coded_grid, &f->decoded_grid);
  f->moved = gop.dynamic_set;
  ApplyMotion(options_.grid, f->decoded_grid, gop.decoded_mlp, &f->moved);
  return f->motion_on ? DecideMotionModes(f) : Status::Ok();
}

Status SequenceEncoder::EstimateMotion(InterFrame* f) {
  Gop& gop = *gop_;
  if (callbacks_.stage) callbacks_.stage("motion", f->frame);
  const MotionEstimationOptions o =
      FrameMotionOptions(options_, f->frame, f->length, !gop.mlp_trained, f->views.size());
  M4D_RETURN_IF_ERROR(estimator_->Estimate(f->views, gop.static_set, gop.dynamic_set, gop.box, o,
                                           &f->motion, gop.static_views.get()));
  f->appearance_check_views = AppearanceCheckViews(f->views.size(), o.appearance_check_every);
  if (!gop.mlp_trained) {
    gop.mlp = estimator_->mlp();
    M4D_RETURN_IF_ERROR(DecodedMlp(gop.mlp, options_, &gop.decoded_mlp));
    gop.mlp_trained = true;
  }
  return Status::Ok();
}

Status SequenceEncoder::RequiredGain(const InterFrame& f, double* required) const {
  // The set the grid is read at: the keyframe's until the keyframe is written with this frame.
  const GaussianSet& read_by =
      gop_->keyframe_pending ? gop_->dynamic_set : writer_->moved_dynamic_set();
  std::vector<uint8_t> grid, appearance;
  M4D_RETURN_IF_ERROR(writer_->MotionPayload(f.coded_grid, read_by, &grid));
  M4D_RETURN_IF_ERROR(
      writer_->AppearancePayload(f.appearance.step, f.motion.appearance, &appearance));
  *required =
      RequiredAppearanceGain(options_.appearance_min_gain, options_.appearance_gain_per_doubling,
                             grid.size(), appearance.size());
  return Status::Ok();
}

// The colour change is decided first, so that the motion is judged with what it would code.
Status SequenceEncoder::DecideMotionModes(InterFrame* f) {
  Gop& gop = *gop_;
  FrameReport& report = f->report;
  if (!f->motion.appearance.empty()) {
    f->appearance.step = options_.motion.appearance_step;
    f->appearance.values.assign(f->motion.appearance.begin(), f->motion.appearance.end());
    double required = 0;
    M4D_RETURN_IF_ERROR(RequiredGain(*f, &required));
    AppearanceDecision appearance;
    M4D_RETURN_IF_ERROR(DecideAppearance(f->appearance, required, f->appearance_check_views,
                                         gop.meter.get(), &f->moved, &appearance));
    report.appearance_gain = appearance.gain;
    report.appearance_skipped = appearance.skipped;
  }
  MotionDecision motion;
  M4D_RETURN_IF_ERROR(
      DecideMotion(gop.dynamic_set, f->moved, options_.motion_min_gain, gop.meter.get(), &motion));
  report.motion_gain = motion.gain;
  report.motion_skipped = motion.skip;
  if (motion.skip) {
    SkipMotion(&f->coded_grid);
    f->moved = gop.dynamic_set;
    std::fill(f->motion.motion.begin(), f->motion.motion.end(), 0.0f);
    report.appearance_skipped = true;
  }
  return Status::Ok();
}

Status SequenceEncoder::Compensate(InterFrame* f) {
  ClearCompensation(f->moved.size(), options_.sh_degree, &f->compensation);
  if (options_.ablation.compensation) M4D_RETURN_IF_ERROR(TrainFrameCompensation(f));
  CompensationDecision decision;
  M4D_RETURN_IF_ERROR(DecideCompensation(f->moved, options_.compensation_min_gain,
                                         options_.sh_degree, gop_->meter.get(), &f->compensation,
                                         &decision));
  FrameReport& report = f->report;
  report.compensation_abandoned = f->compensation.abandoned;
  report.training_psnr = decision.training_psnr;
  report.compensation_gain = decision.gain;
  report.added = f->compensation.added.size();
  for (uint8_t r : f->compensation.removed) report.removed += r;
  const size_t dynamic = gop_->dynamic_set.size();
  report.ratio =
      dynamic > 0 ? static_cast<double>(report.added) / static_cast<double>(dynamic) : 0.0;
  return Status::Ok();
}

Status SequenceEncoder::TrainFrameCompensation(InterFrame* f) {
  Gop& gop = *gop_;
  if (callbacks_.stage) callbacks_.stage("compensation", f->frame);
  std::vector<float> gradient, blend_weight;
  M4D_RETURN_IF_ERROR(MeasureViewspaceGradients(f->views, gop.static_set, f->moved,
                                                options_.sh_degree, options_.context, &gradient,
                                                gop.static_views.get(), &blend_weight));
  std::vector<float> outputs =
      f->motion_on ? f->motion.motion : std::vector<float>(7 * f->moved.size());
  CompensationCandidates candidates =
      ProposeCompensation(f->moved, gradient, outputs, options_.compensation_thresholds,
                          static_cast<uint32_t>(options_.context.seed + f->frame));
  CompensationSharing sharing;
  sharing.static_views = gop.static_views.get();
  sharing.moved_blend_weight = &blend_weight;
  if (options_.compensation_early_decision) {
    sharing.probe = [&](const GaussianSet& kept, const GaussianSet& added, double* gain) {
      return CompensationGain(f->moved, kept, added, gop.meter.get(), gain);
    };
  }
  return TrainCompensation(f->views, gop.static_set, f->moved, candidates,
                           FrameCompensationOptions(options_, f->frame, gop.scene_extent),
                           &f->compensation, sharing);
}

// The keyframe first if its MLP was just trained, then the frame.
Status SequenceEncoder::WriteInterFrame(InterFrame* f) {
  Gop& gop = *gop_;
  if (gop.keyframe_pending) M4D_RETURN_IF_ERROR(WriteKeyframe());
  FrameReport& report = f->report;
  const Clock::time_point start = Clock::now();
  M4D_RETURN_IF_ERROR(writer_->WriteMotion(f->coded_grid));
  if (!report.appearance_skipped) {
    M4D_RETURN_IF_ERROR(writer_->WriteAppearance(f->appearance.step, f->motion.appearance));
  }
  if (!SameGaussianSet(writer_->moved_dynamic_set(), f->moved)) {
    return Status(M4D_ERR_BITSTREAM, "encoder: moved set differs from the decoder's");
  }
  DecodedFrame recon;
  M4D_RETURN_IF_ERROR(
      writer_->WriteCompensation(f->compensation.removed, f->compensation.added, &recon));
  report.seconds.coding = Since(start);
  report.bytes = writer_->last_frame_bytes();
  report.hash = FrameHashHex(recon);
  gop.dynamic_set = *recon.dynamic_layer;
  return ReportFrame(f->frame, &report);
}

Status SequenceEncoder::ReportFrame(int frame, FrameReport* report) {
  M4D_RETURN_IF_ERROR(EvaluateHeldOut(capture_, frame, gop_->static_set, gop_->dynamic_set,
                                      EncoderRenderSettings(options_), callbacks_.held_out_view,
                                      report));
  report_->frames.push_back(*report);
  if (callbacks_.frame_coded) callbacks_.frame_coded(*report);
  return Status::Ok();
}

Status SequenceEncoder::Restart(int frame) {
  if (gop_->keyframe_pending) M4D_RETURN_IF_ERROR(WriteKeyframe());
  const Clock::time_point start = Clock::now();
  const bool dependent = gop_policy_.Dependent(frame);
  GaussianModel model;
  RetrainingGrowth growth;
  M4D_RETURN_IF_ERROR(Retrain(frame, dependent, &model, &growth));
  const double prediction_psnr = gop_->prediction_psnr;
  if (dependent) {
    GaussianSet kept = std::move(gop_->static_set);
    M4D_RETURN_IF_ERROR(StartDependentGop(frame, std::move(model), std::move(kept), Since(start)));
  } else {
    M4D_RETURN_IF_ERROR(StartGop(frame, std::move(model), Since(start)));
  }
  gop_->keyframe_report.prediction_psnr = prediction_psnr;
  gop_->keyframe_report.seeded = growth.seeded;
  return Status::Ok();
}

Status SequenceEncoder::Retrain(int frame, bool dependent, GaussianModel* model,
                                RetrainingGrowth* growth) {
  // The new keyframe starts from the last decoded frame's whole state (paper section 3.5)
  // moved to this frame, the prediction its inter frame would have coded, and grows what that
  // prediction does not explain (retraining_growth.h).
  GaussianModel start;
  M4D_RETURN_IF_ERROR(CombinedModel(gop_->static_set, gop_->predicted, &start));
  // A dependent GOP keeps the static set exactly: its Gaussians (first in the model) stay.
  KeyframeTrainingOptions o =
      RetrainingOptions(options_, frame, dependent ? gop_->static_set.size() : 0);
  TrainingViews views;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, frame, capture_.TrainCameras(), &views));
  if (o.max_gaussians_per_pixel > 0.0f) {
    RetrainingGrowthOptions g;
    g.gaussians_per_pixel = o.max_gaussians_per_pixel;
    g.unexplained = options_.decoupling.change;
    g.render = EncoderRenderSettings(options_);
    g.seed = o.context.seed;
    M4D_RETURN_IF_ERROR(GrowForUnexplained(views, g, &start, growth));
    o.densification.max_gaussians = std::min(o.densification.max_gaussians, growth->cap);
  }
  KeyframeTrainer trainer;
  M4D_RETURN_IF_ERROR(trainer.Init(o, std::move(views), std::move(start)));
  M4D_RETURN_IF_ERROR(trainer.Train([&](const TrainingProgress& p) {
    if (callbacks_.training) callbacks_.training("retrain", frame, p);
  }));
  *model = trainer.TakeModel();
  return Status::Ok();
}

}  // namespace m4d
