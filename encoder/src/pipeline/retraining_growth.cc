#include "encoder/src/pipeline/retraining_growth.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "encoder/src/train/photo_consistent_points.h"
#include "encoder/src/train/point_initialisation.h"
#include "encoder/src/train/view_evaluation.h"

namespace m4d {
namespace {

void AppendModel(const GaussianModel& extra, GaussianModel* model) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const GaussianParameter parameter = static_cast<GaussianParameter>(p);
    std::vector<float>& values = model->values(parameter);
    const std::vector<float>& more = extra.values(parameter);
    values.insert(values.end(), more.begin(), more.end());
  }
}

// Per view, 1 where the model renders unlike the image; *count: such pixels in all views.
Status UnexplainedMasks(const GaussianModel& model, const TrainingViews& views,
                        const RetrainingGrowthOptions& options,
                        std::vector<std::vector<float>>* masks, size_t* count) {
  masks->assign(static_cast<size_t>(views.size()), {});
  *count = 0;
  RenderContext context;
  Image render;
  for (int v = 0; v < views.size(); ++v) {
    M4D_RETURN_IF_ERROR(RenderView(model, views.cameras[v], options.render, &context, &render));
    TemporalChange change;
    M4D_RETURN_IF_ERROR(
        MeasureTemporalChange(render, views.images[v], options.unexplained, &change));
    for (float m : change.mask) *count += m > 0.0f ? 1 : 0;
    (*masks)[v] = std::move(change.mask);
  }
  return Status::Ok();
}

// The box of the model's positions: seeds inside it leave the coded position range as the
// prediction has it (photo_consistent_points.h).
void BoundByModel(const GaussianModel& model, PhotoConsistencyOptions* photo) {
  if (model.size() == 0) return;
  photo->bounded = true;
  for (int a = 0; a < 3; ++a) {
    photo->box_min[a] = photo->box_max[a] = model.positions[a];
  }
  for (size_t i = 0; i < model.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      photo->box_min[a] = std::min(photo->box_min[a], model.positions[3 * i + a]);
      photo->box_max[a] = std::max(photo->box_max[a], model.positions[3 * i + a]);
    }
  }
}

}  // namespace

Status GrowForUnexplained(const TrainingViews& views, const RetrainingGrowthOptions& options,
                          GaussianModel* model, RetrainingGrowth* growth) {
  if (!(options.gaussians_per_pixel >= 0.0f) || !std::isfinite(options.gaussians_per_pixel)) {
    return Status(M4D_ERR_INVALID_ARG, "retraining growth: Gaussians per pixel");
  }
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  *growth = RetrainingGrowth();
  std::vector<std::vector<float>> masks;
  M4D_RETURN_IF_ERROR(
      UnexplainedMasks(*model, views, options, &masks, &growth->unexplained_pixels));
  const size_t bound = static_cast<size_t>(
      std::floor(options.gaussians_per_pixel * static_cast<double>(growth->unexplained_pixels)));
  growth->cap = model->size() + bound;
  if (bound / 2 == 0) return Status::Ok();
  PhotoConsistencyOptions photo;
  photo.points = bound / 2;  // the other half is left to densification
  photo.ray_masks = &masks;
  photo.seed = options.seed;
  photo.threads = options.render.threads;
  BoundByModel(*model, &photo);
  PointCloud points;
  M4D_RETURN_IF_ERROR(PhotoConsistentPoints(views, photo, &points));
  if (points.size() == 0) return Status::Ok();
  PointInitialisationOptions init;
  init.sh_degree = model->sh_degree;
  init.opacity = options.seed_opacity;
  init.threads = options.render.threads;
  GaussianModel seeds;
  M4D_RETURN_IF_ERROR(InitialiseFromPoints(points, init, &seeds));
  AppendModel(seeds, model);
  growth->seeded = seeds.size();
  return Status::Ok();
}

}  // namespace m4d
