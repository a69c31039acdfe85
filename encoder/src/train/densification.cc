#include "encoder/src/train/densification.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/train/row_edit.h"

namespace m4d {
namespace {

float Logit(float p) { return std::log(p / (1.0f - p)); }

float MaxScale(const GaussianModel& model, size_t i) {
  const float* s = &model.log_scales[3 * i];
  return std::exp(std::max({s[0], s[1], s[2]}));
}

// The Gaussians that densify: mean gradient at or above the threshold, at most `budget` of
// them (largest gradients first, ties to the lower index), in index order.
std::vector<uint32_t> Candidates(const DensificationStats& stats, float threshold, size_t budget) {
  std::vector<uint32_t> selected;
  for (size_t i = 0; i < stats.size(); ++i) {
    if (stats.MeanGradient(i) >= threshold) selected.push_back(static_cast<uint32_t>(i));
  }
  if (selected.size() > budget) {
    std::stable_sort(selected.begin(), selected.end(), [&](uint32_t a, uint32_t b) {
      return stats.MeanGradient(a) > stats.MeanGradient(b);
    });
    selected.resize(budget);
    std::sort(selected.begin(), selected.end());
  }
  return selected;
}

// Moves rows [first, first + 2 parents) (children: all first copies, then all second
// copies) to samples of their parent's Gaussian and shrinks their scales.
void PlaceSplitChildren(const std::vector<uint32_t>& parents, size_t first, float scale_divisor,
                        TrainingRandom* rng, GaussianModel* model) {
  const float log_divisor = std::log(scale_divisor);
  for (size_t c = 0; c < 2 * parents.size(); ++c) {
    const size_t row = first + c;
    const uint32_t parent = parents[c % parents.size()];
    float r[9];
    QuaternionMatrix(&model->rotations[4 * size_t{parent}], r);
    float sample[3];
    for (int a = 0; a < 3; ++a) {
      sample[a] = rng->Normal() * std::exp(model->log_scales[3 * size_t{parent} + a]);
    }
    for (int a = 0; a < 3; ++a) {
      model->positions[3 * row + a] = model->positions[3 * size_t{parent} + a] +
                                      r[3 * a] * sample[0] + r[3 * a + 1] * sample[1] +
                                      r[3 * a + 2] * sample[2];
      model->log_scales[3 * row + a] = model->log_scales[3 * size_t{parent} + a] - log_divisor;
    }
  }
}

}  // namespace

void DensificationStats::Reset(size_t count) {
  gradient_sum_.assign(count, 0.0f);
  views_.assign(count, 0);
  max_radius_.assign(count, 0.0f);
}

void DensificationStats::Keep(const std::vector<uint8_t>& keep) {
  KeepRows(keep, 1, &gradient_sum_);
  KeepRows(keep, 1, &views_);
  KeepRows(keep, 1, &max_radius_);
}

void DensificationStats::Accumulate(const ProjectedSplats& splats, const float* mean2d, int width,
                                    int height) {
  const size_t n = std::min(size(), splats.size());
  for (size_t i = 0; i < n; ++i) {
    const float radius = splats.radius[i];
    if (!(radius > 0.0f)) continue;
    gradient_sum_[i] += ViewspaceGradientNorm(&mean2d[2 * i], width, height);
    views_[i] += 1;
    max_radius_[i] = std::max(max_radius_[i], radius);
  }
}

void KeepGaussians(const std::vector<uint8_t>& keep, GaussianModel* model, AdamOptimizer* optimizer,
                   DensificationStats* stats) {
  model->Keep(keep);
  optimizer->KeepRows(keep);
  if (stats != nullptr) stats->Keep(keep);
}

Status DensifyAndPrune(const DensificationSettings& settings, float scene_extent,
                       bool prune_by_size, TrainingRandom* rng, GaussianModel* model,
                       AdamOptimizer* optimizer, DensificationStats* stats, DensifyCounts* counts) {
  const size_t n = model->size();
  if (optimizer->rows() != n || stats->size() != n) {
    return Status(M4D_ERR_INVALID_ARG, "densification: model, optimizer and statistics differ");
  }
  if (!(scene_extent > 0.0f)) {
    return Status(M4D_ERR_INVALID_ARG, "densification: the scene extent must be positive");
  }
  // Each clone or split adds one Gaussian.
  const size_t budget = settings.max_gaussians > n ? settings.max_gaussians - n : 0;
  const float dense_limit = settings.percent_dense * scene_extent;
  std::vector<uint32_t> clones, parents;
  for (uint32_t i : Candidates(*stats, settings.gradient_threshold, budget)) {
    (i < settings.frozen || MaxScale(*model, i) <= dense_limit ? clones : parents).push_back(i);
  }
  // Rows: originals, clones, first children, second children.
  std::vector<uint32_t> copies = clones;
  copies.insert(copies.end(), parents.begin(), parents.end());
  copies.insert(copies.end(), parents.begin(), parents.end());
  std::vector<float> radii(n);
  for (size_t i = 0; i < n; ++i) radii[i] = stats->max_radius(i);
  model->AppendCopies(copies);
  optimizer->AppendZeroRows(copies.size());
  AppendRowCopies(clones, 1, &radii);
  AppendZeroRows(2 * parents.size(), 1, &radii);
  PlaceSplitChildren(parents, n + clones.size(), settings.split_scale_divisor, rng, model);

  const size_t total = model->size();
  std::vector<uint8_t> keep(total, 1);
  for (uint32_t p : parents) keep[p] = 0;
  const float min_logit = Logit(settings.min_opacity);
  const float world_limit = settings.max_world_scale * scene_extent;
  // (priority, row): size-pruned rows first (-infinity), then by opacity.
  std::vector<std::pair<float, uint32_t>> prune;
  for (size_t i = settings.frozen; i < total; ++i) {
    if (!keep[i]) continue;
    const float logit = model->opacity_logits[i];
    const bool by_size =
        prune_by_size &&
        ((settings.max_screen_radius > 0 && radii[i] > settings.max_screen_radius) ||
         MaxScale(*model, i) > world_limit);
    if (by_size || !(logit >= min_logit)) {
      prune.emplace_back(by_size || std::isnan(logit) ? -INFINITY : logit,
                         static_cast<uint32_t>(i));
    }
  }
  const size_t limit = static_cast<size_t>(settings.max_prune_fraction * static_cast<float>(total));
  if (prune.size() > limit) {
    std::nth_element(prune.begin(), prune.begin() + limit, prune.end());
    prune.resize(limit);
  }
  for (const auto& p : prune) keep[p.second] = 0;
  const size_t pruned = prune.size();
  model->Keep(keep);
  optimizer->KeepRows(keep);
  stats->Reset(model->size());
  if (counts != nullptr) *counts = {clones.size(), parents.size(), pruned};
  return Status::Ok();
}

void ResetOpacity(float max_opacity, GaussianModel* model, AdamOptimizer* optimizer) {
  const float max_logit = Logit(max_opacity);
  for (float& logit : model->opacity_logits) logit = std::min(logit, max_logit);
  optimizer->ResetMoments(kParamOpacityLogits);
}

}  // namespace m4d
