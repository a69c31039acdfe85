// What a later keyframe's retraining may add, and where it starts growing it. The retraining
// starts from the frame's prediction, which already explains most pixels; the pixels it does
// not explain (rendered unlike the image by more than the view's own residual explains:
// temporal_change.h with the render as the "before" image) are content that appeared or that
// motion could not reach.
// - Bound: the per-pixel bound (KeyframeTrainingOptions::max_gaussians_per_pixel) over those
//   pixels, not over the whole views. Over the whole views, a retraining that starts below the cap
//   (after importance pruning) refilled the room with Gaussians the views do not need: on the
//   realistic scene it added several times as many static Gaussians as from an unpruned start, and
//   its keyframe grew threefold (docs/results/2026-11-30-readme-notebook.md, "Faint Gaussians
//   removed").
// - Seeds: photo-consistent points cast from those pixels, half the bound, so new content starts
//   where it is instead of waiting for densification to creep to it from the nearest Gaussians (the
//   default scene's object appearing at frame 10 left the retrained keyframe well below the frame
//   before it on the training views: docs/results/2026-11-30-readme-notebook.md, "A later keyframe
//   grows what its prediction does not explain"; docs/results/2026-11-30-comment-measurements.md).
//   Only inside the box of the prediction's positions, so that they do not stretch its coded
//   position range.
#ifndef M4D_ENCODER_PIPELINE_RETRAINING_GROWTH_H_
#define M4D_ENCODER_PIPELINE_RETRAINING_GROWTH_H_

#include <cstddef>
#include <cstdint>

#include "encoder/src/decoupling/temporal_change.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct RetrainingGrowthOptions {
  float gaussians_per_pixel = 0.25f;  // KeyframeTrainingOptions::max_gaussians_per_pixel
  TemporalChangeOptions unexplained;  // render against image
  RenderSettings render;              // threads, SH degree and background of the prediction
  uint64_t seed = 0;
  // Seeds start nearly transparent, unlike a first keyframe's points: sparse seeds take large
  // scales from their few neighbours, and opaque ones veiled the prediction (the training views
  // collapsed at the retraining's first steps on the default scene and on Panoptic basketball),
  // which the retraining did not fully repair. Nearly transparent, they gave better dependent
  // keyframes on both; the realistic scene's three training views gained at its held-out camera's
  // expense (docs/results/2026-11-30-readme-notebook.md, "The 60-frame default scene with bitstream
  // 0.5"; docs/results/2026-11-30-comment-measurements.md).
  float seed_opacity = 0.01f;
};

struct RetrainingGrowth {
  size_t unexplained_pixels = 0;  // over all the views
  size_t seeded = 0;              // Gaussians appended to the model
  size_t cap = 0;                 // for the retraining's densification: the model before
                                  // seeding plus gaussians_per_pixel x unexplained_pixels
};

// Renders *model (the prediction) in every view, appends the seeds to it and returns the cap.
// M4D_ERR_INVALID_ARG for views without images of their cameras' size or bad options.
Status GrowForUnexplained(const TrainingViews& views, const RetrainingGrowthOptions& options,
                          GaussianModel* model, RetrainingGrowth* growth);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_RETRAINING_GROWTH_H_
