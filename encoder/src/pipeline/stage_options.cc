#include "encoder/src/pipeline/stage_options.h"

#include <algorithm>
#include <cstdint>

#include "encoder/src/capture/up_axis_estimate.h"
#include "encoder/src/pipeline/motion_rate_schedule.h"

namespace m4d {

KeyframeTrainingOptions FirstKeyframeTraining(const EncoderOptions& options) {
  KeyframeTrainingOptions o = options.keyframe;
  o.sh_degree = options.sh_degree;
  o.context = options.context;
  o.quantization = options.keyframe_trained_for.value_or(options.quantization);
  o.rate_weight = options.keyframe_rate_weight;
  return o;
}

KeyframeTrainingOptions RetrainingOptions(const EncoderOptions& options, int frame, size_t frozen) {
  KeyframeTrainingOptions o = options.keyframe;
  o.frozen_gaussians = frozen;
  o.iterations = options.retrain_iterations;
  o.learning_rates.position.max_steps = options.retrain_iterations;
  o.densify_from = std::min(o.densify_from, options.retrain_iterations / 4);
  o.densify_until = options.retrain_iterations / 2;
  // Often: content that appeared (the usual reason for a new GOP) has to grow in a short run.
  o.densify_interval = std::max(1, options.retrain_iterations / 20);
  o.opacity_reset_interval = 0;
  o.sh_degree_interval = 0;
  o.coarse_to_fine = CoarseToFineSchedule();  // it starts from a fitted model, not a coarse one
  o.quantization_aware_iterations =
      options.keyframe.quantization_aware_iterations > 0 ? options.retrain_iterations / 4 : 0;
  o.quantization = options.keyframe_trained_for.value_or(options.quantization);
  o.rate_weight = options.keyframe_rate_weight;
  o.start_sh_degree = options.sh_degree;
  o.context = options.context.Reseeded(options.context.seed + static_cast<uint64_t>(frame));
  return o;
}

DecouplingOptions KeyframeDecoupling(const EncoderOptions& options, int frame) {
  DecouplingOptions o = options.decoupling;
  o.context = options.context.Reseeded(options.context.seed + static_cast<uint64_t>(frame));
  return o;
}

MotionEstimationOptions FrameMotionOptions(const EncoderOptions& options, int frame, int length,
                                           bool train_mlp, int view_count) {
  MotionEstimationOptions o = options.motion;
  o.train_mlp = train_mlp;
  if (o.train_mlp) o.iterations = options.first_motion_iterations;
  o.rate_term = options.ablation.rate_term && o.rate_term;
  o.rate_weight = MotionRateWeight(o.rate_weight, length, options.motion_rate_decay);
  if (view_count < options.appearance_min_views) o.appearance_step = 0.0f;
  if (view_count < 2 * o.appearance_check_every) o.appearance_check_every = 0;
  o.sh_degree = options.sh_degree;
  o.context = options.context.Reseeded(options.context.seed + 7919u * static_cast<uint64_t>(frame));
  return o;
}

CompensationOptions FrameCompensationOptions(const EncoderOptions& options, int frame,
                                             float scene_extent) {
  CompensationOptions o = options.compensation;
  o.scene_extent = scene_extent;
  o.sh_degree = options.sh_degree;
  o.context =
      options.context.Reseeded(options.context.seed + 104729u * static_cast<uint64_t>(frame));
  o.probe_min_gain = options.compensation_min_gain;
  return o;
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

RenderSettings EncoderRenderSettings(const EncoderOptions& options) {
  RenderSettings settings;
  settings.sh_degree = options.sh_degree;
  options.context.ApplyTo(&settings);
  return settings;
}

}  // namespace m4d
