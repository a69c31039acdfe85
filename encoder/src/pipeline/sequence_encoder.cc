#include "encoder/src/pipeline/sequence_encoder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "encoder/src/capture/up_axis_estimate.h"
#include "encoder/src/compensation/compensation_candidates.h"
#include "encoder/src/compensation/compensation_training.h"
#include "encoder/src/decoupling/lookahead_decoupling.h"
#include "encoder/src/decoupling/temporal_change.h"
#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/layers/mlp_writer.h"
#include "encoder/src/layers/motion_grid_writer.h"
#include "encoder/src/layers/same_gaussian_set.h"
#include "encoder/src/pipeline/motion_rate_schedule.h"
#include "encoder/src/pipeline/retraining_growth.h"
#include "encoder/src/pipeline/training_psnr_meter.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/scene_extent.h"
#include "encoder/src/train/training_views.h"
#include "encoder/src/train/view_evaluation.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/decode/appearance_application.h"
#include "sdk/src/decode/frame_hash.h"
#include "sdk/src/decode/motion_application.h"
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
  double noise_gap = 0;  // NoiseGap, measured at the first inter frame
};

namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

StreamWriterOptions WriterOptions(const EncoderOptions& o, int frames, const Capture& capture) {
  StreamWriterOptions w;
  w.sequence.up_axis = o.up_axis == kUpAxisAuto ? EstimateUpAxis(capture.cameras) : o.up_axis;
  w.sequence.sh_degree = o.sh_degree;
  w.sequence.fps_num = o.fps_num;
  w.sequence.fps_den = o.fps_den;
  w.sequence.num_frames =
      o.stream_frame_count > 0 ? o.stream_frame_count : static_cast<uint32_t>(frames);
  w.first_frame_index = o.stream_first_index;
  w.sequence.grid = o.grid;
  w.sequence.mlp = o.mlp;
  w.quantization = o.quantization;
  w.compensation_quantization = o.compensation_quantization;
  w.mlp_bits = o.mlp_bits;
  return w;
}

// The MLP as a decoder reads it from the keyframe packet.
Status DecodedMlp(const MlpWeights& mlp, const EncoderOptions& o, MlpWeights* decoded) {
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  M4D_RETURN_IF_ERROR(WriteMlpWeights(mlp, o.mlp_bits, RansLayout::kInterleaved, &writer));
  ByteReader reader(payload.data(), payload.size());
  return ReadMlpWeights(&reader, RansLayout::kInterleaved, o.grid.feature_count(), o.mlp, decoded);
}

// The rounded grid of a motion estimation, dense, in the writer's and the decoder's forms.
void DenseGrids(const GridConfig& config, const float* steps, const MotionEstimationResult* motion,
                const GridBox& box, FloatMotionGrid* coded, MotionGrid* decoded) {
  for (int a = 0; a < 3; ++a) {
    coded->box_min[a] = decoded->box_min[a] = box.min[a];
    coded->box_scale[a] = decoded->box_scale[a] = box.scale[a];
  }
  for (int l = 0; l < kMaxGridLevels; ++l) {
    coded->step[l] = decoded->step[l] = steps[l];
    const size_t size = l < config.num_levels ? config.level_values(l) : 0;
    coded->values[l].assign(size, 0.0f);
    decoded->values[l].assign(size, 0);
    decoded->nonzero_bricks[l].clear();
    if (!motion || l >= config.num_levels) continue;
    const int channels = config.channels[l];
    const std::vector<uint32_t>& active = motion->stencil.active[l];
    const std::vector<float>& values = motion->parameters.grid[l];
    for (size_t v = 0; v < active.size(); ++v) {
      for (int c = 0; c < channels; ++c) {
        const float q = values[v * channels + c];
        const size_t index = static_cast<size_t>(active[v]) * channels + c;
        coded->values[l][index] = q * steps[l];
        decoded->values[l][index] = static_cast<int16_t>(q);
      }
    }
  }
}

// A frame without motion: a grid box that no finite position lies in (its lower corner at the
// largest float), so the decoder leaves every Gaussian unchanged (bitstream-spec 6.3, step 1)
// whatever the grid and MLP hold; every brick is zero, so the grid costs a few bytes.
void SkipMotion(FloatMotionGrid* grid) {
  for (int a = 0; a < 3; ++a) {
    grid->box_min[a] = std::numeric_limits<float>::max();
    grid->box_scale[a] = 1.0f;
  }
  for (std::vector<float>& level : grid->values) std::fill(level.begin(), level.end(), 0.0f);
}

// A model of both sets, static first, at the stream's SH degree.
Status CombinedModel(const GaussianSet& static_set, const GaussianSet& dynamic_set,
                     GaussianModel* model) {
  GaussianModel other;
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(static_set, static_set.sh_degree, model));
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(dynamic_set, static_set.sh_degree, &other));
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    std::vector<float>& to = model->values(param);
    const std::vector<float>& from = other.values(param);
    to.insert(to.end(), from.begin(), from.end());
  }
  return Status::Ok();
}

// Appends the Gaussians of `from` not flagged in `removed` (null: all of them) to *to.
void AppendKept(const GaussianSet& from, const std::vector<uint8_t>* removed, GaussianSet* to) {
  const size_t k = static_cast<size_t>(from.sh_floats());
  for (size_t i = 0; i < from.size(); ++i) {
    if (removed && (*removed)[i]) continue;
    const size_t j = to->size();
    to->Resize(j + 1);
    std::copy_n(&from.positions[3 * i], 3, &to->positions[3 * j]);
    std::copy_n(&from.log_scales[3 * i], 3, &to->log_scales[3 * j]);
    std::copy_n(&from.rotations[4 * i], 4, &to->rotations[4 * j]);
    to->opacity_logits[j] = from.opacity_logits[i];
    std::copy_n(&from.sh[k * i], k, &to->sh[k * j]);
  }
}

Status EmptySet(int sh_degree, GaussianSet* set) {
  *set = GaussianSet();
  set->sh_degree = sh_degree;
  return Status::Ok();
}

}  // namespace

Status ValidateEncoderOptions(const EncoderOptions& o) {
  auto bad = [](const char* what) {
    return Status(M4D_ERR_INVALID_ARG, std::string("encoder options: ") + what);
  };
  if (o.sh_degree < 0 || o.sh_degree > 3) return bad("SH degree must be 0..3");
  if (o.up_axis < kUpAxisAuto || o.up_axis > 6) return bad("up axis must be auto or 0..6");
  if (o.first_frame < 0 || o.frame_count < 0) return bad("negative frame range");
  if (o.lookahead_frames < 1) return bad("lookahead must be at least one frame");
  if (o.lookahead_step < 1) return bad("lookahead step must be at least one frame");
  if (o.retrain_iterations < 1) return bad("retrain iterations must be positive");
  if (o.first_motion_iterations < 0 || o.motion.iterations < 0) return bad("motion iterations");
  if (!(o.motion_rate_decay >= 0 && o.motion_rate_decay <= 1)) return bad("motion rate decay");
  if (o.gop.max_length < 1 || o.gop.min_length < 1 || o.gop.fixed_length < 0) {
    return bad("GOP lengths");
  }
  if (!(o.gop.threshold >= 0.0f)) return bad("GOP threshold");
  if (!std::is_sorted(o.gop.starts.begin(), o.gop.starts.end())) return bad("GOP starts");
  if (!(o.gop.random_access_seconds >= 0.0 && o.gop.random_access_seconds <= 1e6)) {
    return bad("random-access interval");
  }
  if (!std::isfinite(o.compensation_min_gain)) return bad("compensation minimum gain");
  if (!std::isfinite(o.motion_min_gain)) return bad("motion minimum gain");
  for (int l = 0; l < o.grid.num_levels; ++l) {
    if (!(o.grid_steps[l] > 0.0f)) return bad("grid steps must be positive");
  }
  return ValidateTrainingOptions(o.keyframe);
}

SequenceEncoder::SequenceEncoder(const Capture& capture, const EncoderOptions& options)
    : capture_(capture), options_(options) {}

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

KeyframeTrainingOptions FirstKeyframeTraining(const EncoderOptions& options) {
  KeyframeTrainingOptions o = options.keyframe;
  o.sh_degree = options.sh_degree;
  o.threads = options.threads;
  o.seed = options.seed;
  o.quantization = options.quantization;
  o.rate_weight = options.keyframe_rate_weight;
  std::copy(options.background, options.background + 3, o.background);
  return o;
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
  if (!dependent) random_access_start_ = frame;
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
  DecouplingOptions decoupling = options_.decoupling;
  decoupling.threads = options_.threads;
  decoupling.seed = options_.seed + static_cast<uint64_t>(frame);
  std::copy(options_.background, options_.background + 3, decoupling.background);
  DecouplingResult result;
  M4D_RETURN_IF_ERROR(
      DecoupleKeyframe(model, views, steps, gop_->scene_extent, decoupling, &result));
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
  gop.meter.reset();
  gop.static_views =
      std::make_unique<FrozenLayerViews>(LayerView(gop.static_set), Settings(), views.size());
  gop.meter =
      std::make_unique<TrainingPsnrMeter>(gop.static_set, Settings(), gop.static_views.get());
  M4D_RETURN_IF_ERROR(gop.meter->StartFrame(views));
  M4D_RETURN_IF_ERROR(gop.meter->Measure(gop.dynamic_set, &gop.keyframe_report.training_psnr));
  gop.box = DynamicGridBox(gop.dynamic_set, 0.005f, 0.995f, 0.15f);
  estimator_->StartGop(options_.seed + static_cast<uint64_t>(frame));
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
  M4D_RETURN_IF_ERROR(Evaluate(gop.start, gop.static_set, gop.dynamic_set, &report));
  report_->frames.push_back(report);
  if (callbacks_.frame_coded) callbacks_.frame_coded(report);
  return Status::Ok();
}

Status SequenceEncoder::EncodeInterFrame(int frame, bool* restart) {
  Gop& gop = *gop_;
  const int length = frame - gop.start;  // frames in the GOP so far
  const std::vector<int>& starts = options_.gop.starts;
  const bool fixed = !options_.gop.adaptive && options_.gop.fixed_length > 0;
  const bool imposed = std::binary_search(starts.begin(), starts.end(), frame);
  if (imposed || (starts.empty() && (length >= options_.gop.max_length ||
                                     (fixed && length >= options_.gop.fixed_length)))) {
    *restart = true;
    gop.predicted = gop.dynamic_set;  // no motion estimated: the last frame's
    gop.prediction_psnr = 0;
    return Status::Ok();
  }
  FrameReport report;
  report.frame_index = static_cast<uint32_t>(frame);
  TrainingViews views;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, frame, capture_.TrainCameras(), &views));
  M4D_RETURN_IF_ERROR(gop.meter->StartFrame(views));

  // Motion estimation, then the decoder's moved set.
  Clock::time_point start = Clock::now();
  const bool motion_on = options_.ablation.motion_estimation && gop.dynamic_set.size() > 0;
  MotionEstimationResult motion;
  if (motion_on) {
    if (callbacks_.stage) callbacks_.stage("motion", frame);
    MotionEstimationOptions o = options_.motion;
    o.train_mlp = !gop.mlp_trained;
    if (o.train_mlp) o.iterations = options_.first_motion_iterations;
    o.rate_term = options_.ablation.rate_term && o.rate_term;
    o.rate_weight = MotionRateWeight(o.rate_weight, length, options_.motion_rate_decay);
    if (views.size() < options_.appearance_min_views) o.appearance_step = 0.0f;
    o.sh_degree = options_.sh_degree;
    o.threads = options_.threads;
    o.seed = options_.seed + 7919u * static_cast<uint64_t>(frame);
    std::copy(options_.background, options_.background + 3, o.background);
    M4D_RETURN_IF_ERROR(estimator_->Estimate(views, gop.static_set, gop.dynamic_set, gop.box, o,
                                             &motion, gop.static_views.get()));
    if (!gop.mlp_trained) {
      gop.mlp = estimator_->mlp();
      M4D_RETURN_IF_ERROR(DecodedMlp(gop.mlp, options_, &gop.decoded_mlp));
      gop.mlp_trained = true;
    }
  }
  FloatMotionGrid coded_grid;
  MotionGrid decoded_grid;
  DenseGrids(options_.grid, options_.grid_steps, motion_on ? &motion : nullptr, gop.box,
             &coded_grid, &decoded_grid);
  GaussianSet moved = gop.dynamic_set;
  ApplyMotion(options_.grid, decoded_grid, gop.decoded_mlp, &moved);
  AppearanceUpdate appearance;
  if (motion_on && !motion.appearance.empty()) {
    appearance.step = options_.motion.appearance_step;
    appearance.values.assign(motion.appearance.begin(), motion.appearance.end());
    M4D_RETURN_IF_ERROR(DecideAppearance(appearance, &moved, &report));
  }
  if (motion_on) {
    bool skip = false;
    M4D_RETURN_IF_ERROR(DecideMotion(gop.dynamic_set, moved, &skip, &report));
    if (skip) {
      SkipMotion(&coded_grid);
      moved = gop.dynamic_set;
      std::fill(motion.motion.begin(), motion.motion.end(), 0.0f);
      report.appearance_skipped = true;
    }
  }
  report.seconds.motion = Since(start);

  // Compensation.
  start = Clock::now();
  CompensationResult compensation;
  compensation.removed.assign(moved.size(), 0);
  M4D_RETURN_IF_ERROR(EmptySet(options_.sh_degree, &compensation.added));
  if (options_.ablation.compensation) {
    if (callbacks_.stage) callbacks_.stage("compensation", frame);
    std::vector<float> gradient, blend_weight;
    M4D_RETURN_IF_ERROR(MeasureViewspaceGradients(views, gop.static_set, moved, options_.sh_degree,
                                                  options_.background, options_.threads, &gradient,
                                                  gop.static_views.get(), &blend_weight));
    std::vector<float> outputs = motion_on ? motion.motion : std::vector<float>(7 * moved.size());
    CompensationCandidates candidates =
        ProposeCompensation(moved, gradient, outputs, options_.compensation_thresholds,
                            static_cast<uint32_t>(options_.seed + frame));
    CompensationOptions o = options_.compensation;
    o.scene_extent = gop.scene_extent;
    o.sh_degree = options_.sh_degree;
    o.threads = options_.threads;
    o.seed = options_.seed + 104729u * static_cast<uint64_t>(frame);
    std::copy(options_.background, options_.background + 3, o.background);
    o.probe_min_gain = options_.compensation_min_gain;
    CompensationSharing sharing;
    sharing.static_views = gop.static_views.get();
    sharing.moved_blend_weight = &blend_weight;
    if (options_.compensation_early_decision) {
      sharing.probe = [&](const GaussianSet& kept, const GaussianSet& added, double* gain) {
        return CompensationGain(moved, kept, added, gain);
      };
    }
    M4D_RETURN_IF_ERROR(
        TrainCompensation(views, gop.static_set, moved, candidates, o, &compensation, sharing));
    report.compensation_abandoned = compensation.abandoned;
    if (compensation.abandoned) report.compensation_gain = compensation.probed_gain;
  }
  M4D_RETURN_IF_ERROR(DecideCompensation(moved, &compensation, &report));
  report.seconds.compensation = Since(start);
  report.added = compensation.added.size();
  for (uint8_t r : compensation.removed) report.removed += r;
  report.ratio = gop.dynamic_set.size() > 0 ? static_cast<double>(report.added) /
                                                  static_cast<double>(gop.dynamic_set.size())
                                            : 0.0;
  if (options_.gop.noise_gap && length == 1) M4D_RETURN_IF_ERROR(NoiseGap(views, &gop.noise_gap));
  report.psnr_reference = gop.keyframe_report.training_psnr - gop.noise_gap;
  const double drop = report.psnr_reference - report.training_psnr;
  if (options_.gop.adaptive && starts.empty() && length >= options_.gop.min_length &&
      (report.ratio > options_.gop.threshold ||
       (options_.gop.max_psnr_drop > 0 && drop > options_.gop.max_psnr_drop))) {
    *restart = true;  // frame becomes the next GOP's keyframe; nothing of it is written
    gop.predicted = std::move(moved);
    gop.prediction_psnr = report.training_psnr;
    return Status::Ok();
  }

  // Write: the keyframe first if its MLP was just trained, then this frame.
  if (gop.keyframe_pending) M4D_RETURN_IF_ERROR(WriteKeyframe());
  start = Clock::now();
  M4D_RETURN_IF_ERROR(writer_->WriteMotion(coded_grid));
  if (!report.appearance_skipped) {
    M4D_RETURN_IF_ERROR(writer_->WriteAppearance(appearance.step, motion.appearance));
  }
  if (!SameGaussianSet(writer_->moved_dynamic_set(), moved)) {
    return Status(M4D_ERR_BITSTREAM, "encoder: moved set differs from the decoder's");
  }
  DecodedFrame recon;
  M4D_RETURN_IF_ERROR(writer_->WriteCompensation(compensation.removed, compensation.added, &recon));
  report.seconds.coding = Since(start);
  report.bytes = writer_->last_frame_bytes();
  report.hash = FrameHashHex(recon);
  gop.dynamic_set = *recon.dynamic_layer;
  M4D_RETURN_IF_ERROR(Evaluate(frame, gop.static_set, gop.dynamic_set, &report));
  report_->frames.push_back(report);
  if (callbacks_.frame_coded) callbacks_.frame_coded(report);
  return Status::Ok();
}

Status SequenceEncoder::Restart(int frame) {
  if (gop_->keyframe_pending) M4D_RETURN_IF_ERROR(WriteKeyframe());
  const Clock::time_point start = Clock::now();
  // The new keyframe starts from the last decoded frame's whole state (paper section 3.5)
  // moved to this frame, the prediction its inter frame would have coded, and grows what that
  // prediction does not explain (retraining_growth.h).
  GaussianModel model;
  M4D_RETURN_IF_ERROR(CombinedModel(gop_->static_set, gop_->predicted, &model));
  const bool dependent = DependentGop(frame);
  KeyframeTrainingOptions o = RetrainingOptions(frame, dependent);
  TrainingViews views;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, frame, capture_.TrainCameras(), &views));
  RetrainingGrowth growth;
  if (o.max_gaussians_per_pixel > 0.0f) {
    RetrainingGrowthOptions g;
    g.gaussians_per_pixel = o.max_gaussians_per_pixel;
    g.unexplained = options_.decoupling.change;
    g.render = Settings();
    g.seed = o.seed;
    M4D_RETURN_IF_ERROR(GrowForUnexplained(views, g, &model, &growth));
    o.densification.max_gaussians = std::min(o.densification.max_gaussians, growth.cap);
  }
  KeyframeTrainer trainer;
  M4D_RETURN_IF_ERROR(trainer.Init(o, std::move(views), std::move(model)));
  M4D_RETURN_IF_ERROR(trainer.Train([&](const TrainingProgress& p) {
    if (callbacks_.training) callbacks_.training("retrain", frame, p);
  }));
  const double prediction_psnr = gop_->prediction_psnr;
  if (dependent) {
    GaussianSet kept = std::move(gop_->static_set);
    M4D_RETURN_IF_ERROR(
        StartDependentGop(frame, trainer.TakeModel(), std::move(kept), Since(start)));
  } else {
    M4D_RETURN_IF_ERROR(StartGop(frame, trainer.TakeModel(), Since(start)));
  }
  gop_->keyframe_report.prediction_psnr = prediction_psnr;
  gop_->keyframe_report.seeded = growth.seeded;
  return Status::Ok();
}

KeyframeTrainingOptions SequenceEncoder::RetrainingOptions(int frame, bool dependent) const {
  KeyframeTrainingOptions o = options_.keyframe;
  // A dependent GOP keeps the static set exactly: its Gaussians (first in the model) stay.
  o.frozen_gaussians = dependent ? gop_->static_set.size() : 0;
  o.iterations = options_.retrain_iterations;
  o.learning_rates.position.max_steps = options_.retrain_iterations;
  o.densify_from = std::min(o.densify_from, options_.retrain_iterations / 4);
  o.densify_until = options_.retrain_iterations / 2;
  // Often: content that appeared (the usual reason for a new GOP) has to grow in a short run.
  o.densify_interval = std::max(1, options_.retrain_iterations / 20);
  o.opacity_reset_interval = 0;
  o.sh_degree_interval = 0;
  o.coarse_to_fine = CoarseToFineSchedule();  // it starts from a fitted model, not a coarse one
  o.quantization_aware_iterations =
      options_.keyframe.quantization_aware_iterations > 0 ? options_.retrain_iterations / 4 : 0;
  o.quantization = options_.quantization;
  o.rate_weight = options_.keyframe_rate_weight;
  o.start_sh_degree = options_.sh_degree;
  o.threads = options_.threads;
  o.seed = options_.seed + static_cast<uint64_t>(frame);
  std::copy(options_.background, options_.background + 3, o.background);
  return o;
}

bool SequenceEncoder::DependentGop(int frame) const {
  const double seconds = options_.gop.random_access_seconds;
  if (seconds <= 0.0 || options_.independent_frames) return false;
  const double frames = seconds * options_.fps_num / options_.fps_den;
  return frame - random_access_start_ < static_cast<int>(std::lround(std::max(1.0, frames)));
}

RenderSettings SequenceEncoder::Settings() const {
  RenderSettings settings;
  settings.threads = options_.threads;
  settings.sh_degree = options_.sh_degree;
  std::copy(options_.background, options_.background + 3, settings.background);
  return settings;
}

Status SequenceEncoder::NoiseGap(const TrainingViews& next, double* gap) {
  TrainingViews own;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, gop_->start, capture_.TrainCameras(), &own));
  GaussianModel model;
  M4D_RETURN_IF_ERROR(CombinedModel(gop_->static_set, gop_->dynamic_set, &model));
  double own_error = 0, next_error = 0;
  size_t pixels = 0;
  RenderContext context;
  Image render;
  for (int v = 0; v < own.size() && v < next.size(); ++v) {
    TemporalChange change;
    M4D_RETURN_IF_ERROR(
        MeasureTemporalChange(own.images[v], next.images[v], options_.decoupling.change, &change));
    M4D_RETURN_IF_ERROR(RenderView(model, own.cameras[v], Settings(), &context, &render));
    for (size_t p = 0; p < change.mask.size(); ++p) {
      if (change.mask[p] > 0) continue;
      for (int c = 0; c < 3; ++c) {
        const double a = render.pixels[3 * p + c] - own.images[v].pixels[3 * p + c];
        const double b = render.pixels[3 * p + c] - next.images[v].pixels[3 * p + c];
        own_error += a * a;
        next_error += b * b;
      }
      pixels += 3;
    }
  }
  *gap = pixels > 0 && own_error > 0 && next_error > own_error
             ? 10.0 * std::log10(next_error / own_error)
             : 0.0;
  return Status::Ok();
}

Status SequenceEncoder::DecideMotion(const GaussianSet& still, const GaussianSet& moved, bool* skip,
                                     FrameReport* report) {
  double with = 0, without = 0;
  M4D_RETURN_IF_ERROR(TrainingPsnr(moved, &with));
  M4D_RETURN_IF_ERROR(TrainingPsnr(still, &without));
  report->motion_gain = with - without;
  *skip = !(report->motion_gain > options_.motion_min_gain);
  report->motion_skipped = *skip;
  return Status::Ok();
}

Status SequenceEncoder::DecideAppearance(const AppearanceUpdate& appearance, GaussianSet* moved,
                                         FrameReport* report) {
  GaussianSet changed = *moved;
  ApplyAppearanceUpdate(appearance, &changed);
  double with = 0, without = 0;
  M4D_RETURN_IF_ERROR(TrainingPsnr(changed, &with));
  M4D_RETURN_IF_ERROR(TrainingPsnr(*moved, &without));
  report->appearance_gain = with - without;
  report->appearance_skipped = !(report->appearance_gain > options_.appearance_min_gain);
  if (!report->appearance_skipped) *moved = std::move(changed);
  return Status::Ok();
}

Status SequenceEncoder::CompensationGain(const GaussianSet& moved, const GaussianSet& kept,
                                         const GaussianSet& added, double* gain) {
  GaussianSet coded;
  coded.sh_degree = moved.sh_degree;
  AppendKept(kept, nullptr, &coded);
  AppendKept(added, nullptr, &coded);
  double with = 0, without = 0;
  M4D_RETURN_IF_ERROR(TrainingPsnr(coded, &with));
  M4D_RETURN_IF_ERROR(TrainingPsnr(moved, &without));
  *gain = with - without;
  return Status::Ok();
}

Status SequenceEncoder::DecideCompensation(const GaussianSet& moved,
                                           CompensationResult* compensation, FrameReport* report) {
  GaussianSet coded;  // the frame with its compensation, before the compensation's quantization
  coded.sh_degree = moved.sh_degree;
  AppendKept(moved, &compensation->removed, &coded);
  AppendKept(compensation->added, nullptr, &coded);
  M4D_RETURN_IF_ERROR(TrainingPsnr(coded, &report->training_psnr));
  if (compensation->added.size() == 0 &&
      std::count(compensation->removed.begin(), compensation->removed.end(), 1) == 0) {
    return Status::Ok();
  }
  double without = 0;
  M4D_RETURN_IF_ERROR(TrainingPsnr(moved, &without));
  report->compensation_gain = report->training_psnr - without;
  if (report->compensation_gain >= options_.compensation_min_gain) return Status::Ok();
  compensation->removed.assign(moved.size(), 0);
  M4D_RETURN_IF_ERROR(EmptySet(options_.sh_degree, &compensation->added));
  report->training_psnr = without;
  return Status::Ok();
}

Status SequenceEncoder::TrainingPsnr(const GaussianSet& dynamic_set, double* psnr) {
  return gop_->meter->Measure(dynamic_set, psnr);
}

Status SequenceEncoder::Evaluate(int frame, const GaussianSet& static_set,
                                 const GaussianSet& dynamic_set, FrameReport* report) {
  report->static_count = static_set.size();
  report->dynamic_count = dynamic_set.size();
  if (capture_.test_cameras.empty()) return Status::Ok();
  const Clock::time_point start = Clock::now();
  TrainingViews test;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture_, frame, capture_.test_cameras, &test));
  GaussianModel model;
  M4D_RETURN_IF_ERROR(CombinedModel(static_set, dynamic_set, &model));
  const RenderSettings settings = Settings();
  EvaluationResult result;
  RenderContext context;
  M4D_RETURN_IF_ERROR(EvaluateViews(model, test, settings, &context, &result));
  if (callbacks_.held_out_view) {
    Image render;
    M4D_RETURN_IF_ERROR(RenderView(model, test.cameras[0], settings, &context, &render));
    callbacks_.held_out_view(frame, test.images[0], render);
  }
  report->held_out = true;
  report->psnr = result.mean_psnr;
  report->ssim = result.mean_ssim;
  report->seconds.evaluation = Since(start);
  return Status::Ok();
}

}  // namespace m4d
