#include "encoder/src/compensation/compensation_training.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "encoder/src/metrics/focused_loss.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/raster/viewspace_gradient.h"
#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/densification.h"
#include "encoder/src/train/frozen_layer_views.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/gaussian_optimizer.h"
#include "encoder/src/train/training_random.h"

namespace m4d {
namespace {

RenderSettings Settings(int sh_degree, const EncodeContext& context) {
  RenderSettings settings;
  settings.sh_degree = sh_degree;
  context.ApplyTo(&settings);
  return settings;
}

void CopyRender(const Camera& camera, const RenderContext& context, Image* image) {
  image->width = camera.width;
  image->height = camera.height;
  image->channels = 3;
  image->pixels = context.color;
}

GaussianSet KeepOnly(const GaussianSet& set, const std::vector<uint8_t>& removed) {
  GaussianSet kept;
  kept.sh_degree = set.sh_degree;
  const size_t k = static_cast<size_t>(set.sh_floats());
  for (size_t i = 0; i < set.size(); ++i) {
    if (removed[i]) continue;
    const size_t j = kept.size();
    kept.Resize(j + 1);
    std::copy_n(&set.positions[3 * i], 3, &kept.positions[3 * j]);
    std::copy_n(&set.log_scales[3 * i], 3, &kept.log_scales[3 * j]);
    std::copy_n(&set.rotations[4 * i], 4, &kept.rotations[4 * j]);
    kept.opacity_logits[j] = set.opacity_logits[i];
    std::copy_n(&set.sh[k * i], k, &kept.sh[k * j]);
  }
  return kept;
}

float Sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// model's Gaussians that the pruning would keep, the model itself unchanged.
Status PrunedSet(const GaussianModel& model, float prune_opacity, int sh_degree, GaussianSet* set) {
  GaussianSet all;
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(model, sh_degree, &all));
  std::vector<uint8_t> removed(model.size());
  for (size_t i = 0; i < model.size(); ++i) {
    removed[i] = Sigmoid(model.opacity_logits[i]) < prune_opacity;
  }
  *set = KeepOnly(all, removed);
  return Status::Ok();
}

void Abandon(size_t moved_count, size_t candidate_count, int sh_degree,
             CompensationResult* result) {
  result->abandoned = true;
  result->added = GaussianSet();
  result->added.sh_degree = sh_degree;
  result->removed.assign(moved_count, 0);
  result->removed_unseen = 0;
  result->pruned_added = candidate_count;
}

// Total blend weight over all views of every Gaussian of the layers after layer 0, the static
// one. Their splats lie within the focus on them, so only its tiles are rendered.
Status BlendWeights(const TrainingViews& views, const M4dGaussians* layers, int count,
                    RenderSettings settings, FrozenLayerViews* static_views, RenderContext* context,
                    std::vector<float>* total) {
  settings.blend_weights = true;
  settings.focus_layer = 1;
  settings.focus_margin = 0;
  for (int v = 0; v < views.size(); ++v) {
    const ProjectedSplats* static_projection = nullptr;
    M4D_RETURN_IF_ERROR(static_views->Projection(v, views.cameras[v], &static_projection));
    M4D_RETURN_IF_ERROR(RenderForward(views.cameras[v], layers, count, settings, nullptr,
                                      static_projection, context));
    if (v == 0) total->assign(context->blend_weight.size(), 0.0f);
    for (size_t g = 0; g < total->size(); ++g) (*total)[g] += context->blend_weight[g];
  }
  return Status::Ok();
}

}  // namespace

Status MeasureViewspaceGradients(const TrainingViews& views, const GaussianSet& static_set,
                                 const GaussianSet& moved, int sh_degree,
                                 const EncodeContext& encode, std::vector<float>* mean_gradient,
                                 FrozenLayerViews* static_views, std::vector<float>* blend_weight) {
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  const RenderSettings settings = Settings(sh_degree, encode);
  std::unique_ptr<FrozenLayerViews> own_views;
  if (!static_views) {
    own_views =
        std::make_unique<FrozenLayerViews>(GaussianView(static_set), settings, views.size());
    static_views = own_views.get();
  }
  // The moved set's splats lie within the focus on it; the loss reads the tiles around it
  // from the static layer's render, so their gradients are the whole render's.
  RenderSettings focused = settings;
  focused.focus_layer = 1;
  focused.focus_margin = 0;
  focused.blend_weights = blend_weight != nullptr;
  if (blend_weight) blend_weight->assign(moved.size(), 0.0f);
  const M4dGaussians layers[2] = {GaussianView(static_set), GaussianView(moved)};
  const size_t offset = static_set.size(), n = moved.size();
  std::vector<float> sum(n, 0.0f), mean2d(2 * (offset + n));
  std::vector<int> seen(n, 0);
  LayerGradients frozen[2];
  SplatGradients outputs;
  outputs.layers = frozen;
  outputs.layer_count = 2;
  outputs.mean2d = mean2d.data();
  RenderContext context;
  BackwardWorkspace workspace;
  FocusedLoss loss;
  Image rendered, grad;
  for (int v = 0; v < views.size(); ++v) {
    const Camera& camera = views.cameras[v];
    const ProjectedSplats* static_projection = nullptr;
    M4D_RETURN_IF_ERROR(static_views->Projection(v, camera, &static_projection));
    M4D_RETURN_IF_ERROR(
        RenderForward(camera, layers, 2, focused, nullptr, static_projection, &context));
    CopyRender(camera, context, &rendered);
    const Image* static_render = nullptr;
    M4D_RETURN_IF_ERROR(static_views->Render(v, camera, &static_render));
    PhotometricLossValue value;
    M4D_RETURN_IF_ERROR(
        loss.Evaluate(rendered, views.images[v], context.focus, static_render, &value, &grad));
    M4D_RETURN_IF_ERROR(RenderBackward(grad.pixels.data(), nullptr, &context, outputs, &workspace));
    for (size_t i = 0; blend_weight && i < n; ++i) {
      (*blend_weight)[i] += context.blend_weight[offset + i];
    }
    for (size_t i = 0; i < n; ++i) {
      if (context.splats.radius[offset + i] == 0.0f) continue;
      sum[i] += ViewspaceGradientNorm(&mean2d[2 * (offset + i)], camera.width, camera.height);
      ++seen[i];
    }
  }
  mean_gradient->assign(n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    if (seen[i]) (*mean_gradient)[i] = sum[i] / static_cast<float>(seen[i]);
  }
  return Status::Ok();
}

Status TrainCompensation(const TrainingViews& views, const GaussianSet& static_set,
                         const GaussianSet& moved, const CompensationCandidates& candidates,
                         const CompensationOptions& options, CompensationResult* result,
                         const CompensationSharing& sharing) {
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  result->abandoned = false;
  result->probed_gain = 0;
  if (candidates.removed.size() != moved.size()) {
    return Status(M4D_ERR_INVALID_ARG, "compensation: removal flags differ from the moved set");
  }
  const RenderSettings settings = Settings(options.sh_degree, options.context);
  if (sharing.moved_blend_weight && sharing.moved_blend_weight->size() != moved.size()) {
    return Status(M4D_ERR_INVALID_ARG, "compensation: blend weights differ from the moved set");
  }
  RenderContext context;
  FrozenLayerViews* static_views = sharing.static_views;
  std::unique_ptr<FrozenLayerViews> own_views;
  if (!static_views) {
    own_views =
        std::make_unique<FrozenLayerViews>(GaussianView(static_set), settings, views.size());
    static_views = own_views.get();
  }

  // Moved Gaussians that no training view sees are removed with the split parents.
  result->removed = candidates.removed;
  {
    std::vector<float> weight;
    size_t offset = 0;
    if (sharing.moved_blend_weight) {
      weight = *sharing.moved_blend_weight;
    } else {
      const M4dGaussians layers[2] = {GaussianView(static_set), GaussianView(moved)};
      M4D_RETURN_IF_ERROR(
          BlendWeights(views, layers, 2, settings, static_views, &context, &weight));
      offset = static_set.size();
    }
    result->removed_unseen = 0;
    for (size_t i = 0; i < moved.size(); ++i) {
      if (!result->removed[i] && weight[offset + i] < options.min_blend_weight) {
        result->removed[i] = 1;
        ++result->removed_unseen;
      }
    }
  }
  const GaussianSet kept = KeepOnly(moved, result->removed);

  GaussianModel model, gradients;
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(candidates.added, candidates.added.sh_degree, &model));
  gradients = model;
  AdamOptimizer optimizer =
      MakeGaussianOptimizer(model, options.learning_rates, options.scene_extent);
  LayerGradients layer_grads[3];  // static and moved frozen
  SplatGradients outputs;
  outputs.layers = layer_grads;
  outputs.layer_count = 3;
  BackwardWorkspace workspace;
  FocusedLoss loss(options.ssim_weight);
  Image rendered, grad;
  TrainingRandom rng(options.context.seed);
  std::vector<int> order;
  size_t cursor = 0;
  double color_sum = 0;
  int color_count = 0;
  const size_t initial = model.size();
  RenderSettings focused = settings;
  focused.focus_layer = 1;   // the static layer alone is the same in every step
  focused.focus_margin = 0;  // the loss reads the tiles around from the static render
  auto prune = [&]() {
    std::vector<uint8_t> keep(model.size());
    for (size_t i = 0; i < model.size(); ++i) {
      keep[i] = Sigmoid(model.opacity_logits[i]) >= options.prune_opacity;
    }
    KeepGaussians(keep, &model, &optimizer, nullptr);
    gradients.Resize(model.size());
  };
  for (int it = 1; it <= options.iterations && model.size() > 0; ++it) {
    if (cursor == order.size()) {
      order.resize(views.size());
      for (int v = 0; v < views.size(); ++v) order[v] = v;
      rng.Shuffle(&order);
      cursor = 0;
      color_sum = 0;
      color_count = 0;
    }
    const int view = order[cursor++];
    const M4dGaussians layers[3] = {GaussianView(static_set), GaussianView(kept),
                                    GaussianView(model)};
    const Camera& camera = views.cameras[view];
    const ProjectedSplats* static_projection = nullptr;
    M4D_RETURN_IF_ERROR(static_views->Projection(view, camera, &static_projection));
    M4D_RETURN_IF_ERROR(
        RenderForward(camera, layers, 3, focused, nullptr, static_projection, &context));
    CopyRender(camera, context, &rendered);
    PhotometricLossValue value;
    const Image* static_render = nullptr;
    M4D_RETURN_IF_ERROR(static_views->Render(view, camera, &static_render));
    M4D_RETURN_IF_ERROR(
        loss.Evaluate(rendered, views.images[view], context.focus, static_render, &value, &grad));
    color_sum += value.loss;
    ++color_count;
    layer_grads[2] = GradientView(&gradients);
    M4D_RETURN_IF_ERROR(RenderBackward(grad.pixels.data(), nullptr, &context, outputs, &workspace));
    // lambda_3 times the relaxed L0 norm (see the header): a constant pull on every logit.
    for (float& g : gradients.opacity_logits) g += static_cast<float>(options.sparsity_weight);
    StepGaussianOptimizer(gradients, kGaussianParameterCount, &optimizer, &model, nullptr);
    if (options.prune_interval > 0 && it % options.prune_interval == 0) prune();
    if (sharing.probe && options.probe_iteration >= 2 &&
        (it == options.probe_iteration / 2 || it == options.probe_iteration)) {
      const double before = result->probed_gain;
      GaussianSet added;
      M4D_RETURN_IF_ERROR(
          PrunedSet(model, options.prune_opacity, candidates.added.sh_degree, &added));
      M4D_RETURN_IF_ERROR(sharing.probe(kept, added, &result->probed_gain));
      const double per_iteration =
          (result->probed_gain - before) / (options.probe_iteration - options.probe_iteration / 2);
      const double projected = result->probed_gain + per_iteration * (options.iterations - it);
      if (it == options.probe_iteration && projected < options.probe_min_gain) {
        result->color_loss = color_count ? color_sum / color_count : 0.0;
        Abandon(moved.size(), initial, candidates.added.sh_degree, result);
        return Status::Ok();
      }
    }
  }
  result->color_loss = color_count ? color_sum / color_count : 0.0;
  prune();
  // Added Gaussians that no view sees carry nothing.
  if (model.size() > 0) {
    const M4dGaussians layers[3] = {GaussianView(static_set), GaussianView(kept),
                                    GaussianView(model)};
    std::vector<float> weight;
    M4D_RETURN_IF_ERROR(BlendWeights(views, layers, 3, settings, static_views, &context, &weight));
    std::vector<uint8_t> keep(model.size());
    const size_t offset = static_set.size() + kept.size();
    for (size_t i = 0; i < model.size(); ++i) {
      keep[i] = weight[offset + i] >= options.min_blend_weight;
    }
    KeepGaussians(keep, &model, &optimizer, nullptr);
  }
  result->pruned_added = initial - model.size();
  return ModelToGaussianSet(model, candidates.added.sh_degree, &result->added);
}

}  // namespace m4d
