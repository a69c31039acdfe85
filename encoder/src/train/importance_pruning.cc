#include "encoder/src/train/importance_pruning.h"

#include <algorithm>
#include <numeric>

#include "encoder/src/raster/splat_renderer.h"

namespace m4d {

Status BlendingWeights(const GaussianModel& model, const TrainingViews& views,
                       const RenderSettings& settings, RenderContext* context,
                       BackwardWorkspace* workspace, std::vector<double>* weights) {
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  weights->assign(model.size(), 0.0);
  const M4dGaussians layer = GaussianView(model);
  const LayerGradients frozen = {};
  std::vector<float> ones, color(3 * model.size());
  for (int v = 0; v < views.size(); ++v) {
    const Camera& camera = views.cameras[v];
    M4D_RETURN_IF_ERROR(RenderForward(camera, &layer, 1, settings, nullptr, context));
    ones.assign(3 * static_cast<size_t>(camera.width) * camera.height, 1.0f);
    SplatGradients out;
    out.layers = &frozen;
    out.layer_count = 1;
    out.color = color.data();
    M4D_RETURN_IF_ERROR(RenderBackward(ones.data(), nullptr, context, out, workspace));
    for (size_t i = 0; i < model.size(); ++i) (*weights)[i] += color[3 * i];
  }
  return Status::Ok();
}

std::vector<uint8_t> KeepImportant(const std::vector<double>& weights, double share,
                                   double min_weight, double max_fraction) {
  std::vector<uint32_t> order(weights.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return weights[a] < weights[b]; });
  const double budget = share * std::accumulate(weights.begin(), weights.end(), 0.0);
  std::vector<uint8_t> keep(weights.size(), 1);
  const auto max_removed = static_cast<size_t>(max_fraction * static_cast<double>(weights.size()));
  double removed = 0;
  size_t count = 0;
  for (uint32_t i : order) {
    removed += weights[i];
    const bool in_share = !(removed > budget);
    if (!in_share && (!(weights[i] < min_weight) || count >= max_removed)) break;
    keep[i] = 0;
    ++count;
  }
  return keep;
}

}  // namespace m4d
