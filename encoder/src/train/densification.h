// Adaptive density control of the reference 3DGS: statistics gathered over the views a
// Gaussian was visible in, then cloning (small Gaussians with a large view-space gradient),
// splitting (large ones: two children sampled from the Gaussian, scales divided by 1.6),
// pruning (transparent, or too large on screen or in the world) and the periodic opacity
// reset. Every edit also applies to the optimizer's moments and the statistics, so that their
// rows stay those of the model.
//
// Differences from the reference, on purpose: a hard cap on the Gaussian count (when more
// Gaussians want to densify than the cap allows, those with the largest gradient win), and
// the screen-size test uses the largest radius seen since the last densification (the
// reference zeroes those radii just before testing them, so its test never fires).
#ifndef M4D_ENCODER_TRAIN_DENSIFICATION_H_
#define M4D_ENCODER_TRAIN_DENSIFICATION_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/src/raster/render_settings.h"
#include "encoder/src/raster/viewspace_gradient.h"
#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/training_random.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

struct DensificationSettings {
  // On the mean view-space gradient norm, in the reference's NDC units.
  float gradient_threshold = kReferenceDensifyGradient;
  // Split above, clone at or below this fraction of the scene extent (largest scale).
  float percent_dense = 0.01f;
  float min_opacity = 0.005f;        // prune below
  float max_screen_radius = 20.0f;   // pixels; prune above when pruning by size (0: never)
  float max_world_scale = 0.1f;      // times the extent; prune above when pruning by size
  float split_scale_divisor = 1.6f;  // the reference's 0.8 x 2 children
  size_t max_gaussians = kMaxRenderGaussians;  // hard cap after densification
  // At most this fraction of the Gaussians is pruned in one step, the most transparent first (1: no
  // limit, the reference). A short schedule on a capture without initial points otherwise loses
  // most of its model at the first pruning after the opacity reset, and its quality with it, as on
  // the Panoptic basketball capture (docs/results/2026-11-30-readme-notebook.md, "Training does not
  // collapse"; docs/results/2026-11-30-comment-measurements.md).
  float max_prune_fraction = 1.0f;
  // The first this many Gaussians are held fixed (a kept static set): never split nor pruned;
  // one that qualifies is cloned instead, and the clone is free.
  size_t frozen = 0;
};

// Per Gaussian: summed view-space gradient norms, views visible in, largest screen radius.
class DensificationStats {
 public:
  void Reset(size_t count);
  void Keep(const std::vector<uint8_t>& keep);
  size_t size() const { return views_.size(); }

  // Adds one rendered view: each visible Gaussian (radius > 0) adds the norm of its
  // view-space gradient (mean2d: 2 per Gaussian in pixels, from RenderBackward, converted to
  // NDC units for a width x height image) and raises its largest radius.
  void Accumulate(const ProjectedSplats& splats, const float* mean2d, int width, int height);

  // The mean gradient norm over the views the Gaussian was visible in (0 if none).
  float MeanGradient(size_t i) const {
    return views_[i] > 0 ? gradient_sum_[i] / static_cast<float>(views_[i]) : 0.0f;
  }
  uint32_t views(size_t i) const { return views_[i]; }
  float max_radius(size_t i) const { return max_radius_[i]; }

 private:
  std::vector<float> gradient_sum_;
  std::vector<uint32_t> views_;
  std::vector<float> max_radius_;
};

struct DensifyCounts {
  size_t cloned = 0;
  size_t split = 0;   // parents replaced by two children each
  size_t pruned = 0;  // removed besides the split parents
};

// Clones and splits by the statistics, then prunes (by size too if prune_by_size, as the
// reference does after the first opacity reset; at most max_prune_fraction of the model, the
// lowest opacities first, size-pruned ones before them), then restarts the statistics. Cloned and
// split Gaussians get zero optimizer moments. scene_extent must be positive. Fails with
// M4D_ERR_INVALID_ARG when the model, optimizer and statistics differ in size.
Status DensifyAndPrune(const DensificationSettings& settings, float scene_extent,
                       bool prune_by_size, TrainingRandom* rng, GaussianModel* model,
                       AdamOptimizer* optimizer, DensificationStats* stats, DensifyCounts* counts);

// Keeps the Gaussians with keep[i] != 0 in the model, the optimizer and (if not null) the
// statistics.
void KeepGaussians(const std::vector<uint8_t>& keep, GaussianModel* model, AdamOptimizer* optimizer,
                   DensificationStats* stats);

// Lowers every opacity above max_opacity to it and zeroes the opacity moments (the
// reference's reset, with max_opacity 0.01).
void ResetOpacity(float max_opacity, GaussianModel* model, AdamOptimizer* optimizer);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_DENSIFICATION_H_
