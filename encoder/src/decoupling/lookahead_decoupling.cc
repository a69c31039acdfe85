#include "encoder/src/decoupling/lookahead_decoupling.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/decoupling/lookahead_measures.h"
#include "encoder/src/geometry/nearest_neighbours.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/train/gaussian_optimizer.h"
#include "encoder/src/train/view_evaluation.h"

namespace m4d {
namespace {

// Positions and scales only, no density control, full SH, the keyframe's extent.
KeyframeTrainingOptions FineTuneOptions(const DecouplingOptions& options, int sh_degree,
                                        float scene_extent) {
  KeyframeTrainingOptions o;
  o.iterations = options.fine_tune_iterations;
  o.learning_rates.position = {options.position_learning_rate,
                               0.1f * options.position_learning_rate,
                               std::max(1, options.fine_tune_iterations)};
  o.densify_until = 0;
  o.opacity_reset_interval = 0;
  o.sh_degree_interval = 0;
  o.start_sh_degree = sh_degree;
  o.scene_extent = scene_extent;
  o.context = options.context;
  return o;
}

// Sums over the views of each Gaussian's blend weight and error-weighted blend weight, the
// error of a pixel being the mean absolute error of its channels.
Status ErrorWeights(const GaussianModel& model, const TrainingViews& views,
                    const RenderSettings& settings, std::vector<float>* blend,
                    std::vector<float>* error) {
  blend->assign(model.size(), 0.0f);
  error->assign(model.size(), 0.0f);
  RenderContext context;
  Image rendered;
  std::vector<float> pixel_error;
  RenderSettings weighted = settings;
  weighted.blend_weights = true;
  const M4dGaussians layer = GaussianView(model);
  for (int v = 0; v < views.size(); ++v) {
    M4D_RETURN_IF_ERROR(RenderView(model, views.cameras[v], settings, &context, &rendered));
    const Image& truth = views.images[v];
    pixel_error.resize(static_cast<size_t>(truth.width) * truth.height);
    for (size_t p = 0; p < pixel_error.size(); ++p) {
      float e = 0;
      for (int c = 0; c < 3; ++c)
        e += std::fabs(rendered.pixels[3 * p + c] - truth.pixels[3 * p + c]);
      pixel_error[p] = e / 3.0f;
    }
    M4D_RETURN_IF_ERROR(
        RenderForward(views.cameras[v], &layer, 1, weighted, pixel_error.data(), &context));
    for (size_t i = 0; i < model.size(); ++i) {
      (*blend)[i] += context.blend_weight[i];
      (*error)[i] += context.error_weight[i];
    }
  }
  return Status::Ok();
}

// Per Gaussian of the keyframe model: the share of its blend weight over the step's views on
// pixels that changed since the keyframe's frame, less the blend-weighted changed share of
// those views.
Status ChangeSupport(const GaussianModel& keyframe, const TrainingViews& keyframe_views,
                     const TrainingViews& step, const RenderSettings& settings,
                     const TemporalChangeOptions& options, std::vector<float>* support) {
  if (step.size() != keyframe_views.size() ||
      step.camera_indices != keyframe_views.camera_indices) {
    return Status(M4D_ERR_INVALID_ARG, "decoupling: a lookahead step has other cameras");
  }
  std::vector<float> blend(keyframe.size(), 0.0f), changed(keyframe.size(), 0.0f),
      expected(keyframe.size(), 0.0f);
  RenderContext context;
  RenderSettings weighted = settings;
  weighted.blend_weights = true;
  const M4dGaussians layer = GaussianView(keyframe);
  for (int v = 0; v < step.size(); ++v) {
    TemporalChange change;
    M4D_RETURN_IF_ERROR(
        MeasureTemporalChange(keyframe_views.images[v], step.images[v], options, &change));
    M4D_RETURN_IF_ERROR(
        RenderForward(step.cameras[v], &layer, 1, weighted, change.mask.data(), &context));
    for (size_t i = 0; i < keyframe.size(); ++i) {
      blend[i] += context.blend_weight[i];
      changed[i] += context.error_weight[i];
      expected[i] += context.blend_weight[i] * change.changed_share;
    }
  }
  support->resize(keyframe.size());
  for (size_t i = 0; i < keyframe.size(); ++i) {
    (*support)[i] = blend[i] > 0 ? (changed[i] - expected[i]) / blend[i] : 0.0f;
  }
  return Status::Ok();
}

}  // namespace

void SplitModel(const GaussianModel& model, const std::vector<uint8_t>& flags,
                GaussianModel* selected, GaussianModel* rest) {
  *selected = model;
  *rest = model;
  std::vector<uint8_t> others(flags.size());
  for (size_t i = 0; i < flags.size(); ++i) others[i] = flags[i] ? 0 : 1;
  selected->Keep(flags);
  rest->Keep(others);
}

namespace {

// Keeps, per Gaussian, the largest changes and the smallest error seen so far.
void MergeMeasures(const LookaheadMeasures& step, LookaheadMeasures* all) {
  if (all->size() == 0) {
    *all = step;
    return;
  }
  for (size_t i = 0; i < step.size(); ++i) {
    all->displacement[i] = std::max(all->displacement[i], step.displacement[i]);
    if (!step.change_support.empty()) {
      all->change_support[i] = std::max(all->change_support[i], step.change_support[i]);
    }
    all->scale_change[i] = std::max(all->scale_change[i], step.scale_change[i]);
    if (!(all->error[i] <= step.error[i])) all->error[i] = step.error[i];  // NaN: no pixel
  }
}

// Lowers each Gaussian's error to the keyframe model's own on the keyframe's views where that is
// smaller: a Gaussian that fits its own frame is no fitting artefact, however far its content
// moved from where the fine-tuning could follow it (a thrown ball moves its diameter per frame).
Status KeepKeyframeFit(const GaussianModel& keyframe, const TrainingViews& keyframe_views,
                       const RenderSettings& settings, LookaheadMeasures* measures) {
  std::vector<float> blend, error;
  M4D_RETURN_IF_ERROR(ErrorWeights(keyframe, keyframe_views, settings, &blend, &error));
  for (size_t i = 0; i < keyframe.size(); ++i) {
    if (blend[i] <= 0) continue;
    const float own = error[i] / blend[i];
    if (!(measures->error[i] <= own)) measures->error[i] = own;  // NaN: no pixel at t1
  }
  return Status::Ok();
}

}  // namespace

Status DecoupleKeyframe(const GaussianModel& keyframe, const TrainingViews& keyframe_views,
                        const std::vector<TrainingViews>& steps, float scene_extent,
                        const DecouplingOptions& options, DecouplingResult* result) {
  if (steps.empty()) return Status(M4D_ERR_INVALID_ARG, "decoupling: no lookahead frame");
  RenderSettings settings;
  settings.sh_degree = keyframe.sh_degree;
  options.context.ApplyTo(&settings);
  result->measures = LookaheadMeasures();
  GaussianModel tuned = keyframe;
  for (const TrainingViews& views : steps) {
    KeyframeTrainer trainer;
    M4D_RETURN_IF_ERROR(
        trainer.Init(FineTuneOptions(options, keyframe.sh_degree, scene_extent), views, tuned));
    for (int group : {kGroupShDc, kGroupShRest, kGroupOpacity, kGroupRotation}) {
      if (group < trainer.optimizer()->group_count()) trainer.optimizer()->SetFrozen(group, true);
    }
    M4D_RETURN_IF_ERROR(trainer.Train());
    tuned = trainer.TakeModel();

    std::vector<float> blend, error;
    M4D_RETURN_IF_ERROR(ErrorWeights(tuned, views, settings, &blend, &error));
    LookaheadInput in;
    in.count = keyframe.size();
    in.positions_before = keyframe.positions.data();
    in.positions_after = tuned.positions.data();
    in.log_scales_before = keyframe.log_scales.data();
    in.log_scales_after = tuned.log_scales.data();
    in.blend_weight = blend.data();
    in.error_weight = error.data();
    LookaheadMeasures measures = MeasureLookahead(views.cameras, in);
    if (options.thresholds.change_support > 0) {
      M4D_RETURN_IF_ERROR(ChangeSupport(keyframe, keyframe_views, views, settings, options.change,
                                        &measures.change_support));
    }
    MergeMeasures(measures, &result->measures);
  }
  M4D_RETURN_IF_ERROR(KeepKeyframeFit(keyframe, keyframe_views, settings, &result->measures));

  // The counts of the first two steps, for reports.
  const LookaheadMeasures& m = result->measures;
  const DecouplingThresholds& t = options.thresholds;
  result->initially_dynamic = result->refined_dynamic = 0;
  for (size_t i = 0; i < m.size(); ++i) {
    const bool moved = (m.displacement[i] > t.displacement || m.scale_change[i] > t.scale_change) &&
                       (m.change_support.empty() || m.change_support[i] >= t.change_support);
    result->initially_dynamic += moved;
    result->refined_dynamic += moved && !(m.error[i] > t.error);
  }

  std::vector<uint32_t> neighbours;
  if (t.neighbours > 0 && keyframe.size() > 0) {
    NearestNeighbours knn;
    M4D_RETURN_IF_ERROR(knn.Build(keyframe.positions.data(), keyframe.size()));
    neighbours.resize(keyframe.size() * static_cast<size_t>(t.neighbours));
    knn.QueryAll(keyframe.positions.data(), keyframe.size(), t.neighbours, true,
                 options.context.threads, neighbours.data(), nullptr);
  }
  result->dynamic = ClassifyDynamic(m, t, neighbours);
  SplitModel(keyframe, result->dynamic, &result->dynamic_model, &result->static_model);
  return Status::Ok();
}

}  // namespace m4d
