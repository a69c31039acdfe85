#include "encoder/src/pipeline/training_psnr_meter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "encoder/src/layers/same_gaussian_set.h"
#include "encoder/src/raster/splat_renderer.h"
#include "sdk/src/render/projection_constants.h"

namespace m4d {
namespace {

// Squared error of the (clamped) colours against the image, per tile.
void TileErrors(const float* color, const Image& image, int tiles_x, int tiles_y,
                std::vector<double>* errors) {
  errors->assign(static_cast<size_t>(tiles_x) * tiles_y, 0.0);
  for (int y = 0; y < image.height; ++y) {
    const float* c = color + static_cast<size_t>(y) * image.width * 3;
    const float* t = image.row(y);
    double* row = errors->data() + static_cast<size_t>(y / kTileSize) * tiles_x;
    for (int x = 0; x < image.width; ++x) {
      double e = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = static_cast<double>(std::clamp(c[3 * x + k], 0.0f, 1.0f)) - t[3 * x + k];
        e += d * d;
      }
      row[x / kTileSize] += e;
    }
  }
}

double PsnrFromSquaredError(double error, size_t samples) {
  if (error == 0) return std::numeric_limits<double>::infinity();
  return -10.0 * std::log10(error / static_cast<double>(samples));
}

}  // namespace

TrainingPsnrMeter::TrainingPsnrMeter(const GaussianSet& static_set, const RenderSettings& settings,
                                     FrozenLayerViews* static_views)
    : static_set_(static_set), settings_(settings), static_views_(static_views) {}

Status TrainingPsnrMeter::StartFrame(const TrainingViews& views) {
  views_ = &views;
  measured_.clear();
  static_error_.resize(views.size());
  for (int v = 0; v < views.size(); ++v) {
    const Camera& camera = views.cameras[v];
    const Image* static_render = nullptr;
    M4D_RETURN_IF_ERROR(static_views_->Render(v, camera, &static_render));
    TileErrors(static_render->pixels.data(), views.images[v],
               (camera.width + kTileSize - 1) / kTileSize,
               (camera.height + kTileSize - 1) / kTileSize, &static_error_[v]);
  }
  return Status::Ok();
}

Status TrainingPsnrMeter::Measure(const GaussianSet& dynamic_set, double* psnr) {
  if (!views_) return Status(M4D_ERR_INVALID_ARG, "training PSNR: no frame started");
  for (const Measured& m : measured_) {
    if (SameGaussianSet(m.set, dynamic_set)) {
      *psnr = m.psnr;
      return Status::Ok();
    }
  }
  double sum = 0;
  for (int v = 0; v < views_->size(); ++v) {
    double view_psnr = 0;
    M4D_RETURN_IF_ERROR(ViewPsnr(dynamic_set, v, &view_psnr));
    sum += view_psnr;
  }
  *psnr = sum / std::max(1, views_->size());
  measured_.push_back({dynamic_set, *psnr});
  return Status::Ok();
}

Status TrainingPsnrMeter::MeasureViews(const GaussianSet& dynamic_set,
                                       const std::vector<int>& views, double* psnr) {
  if (!views_) return Status(M4D_ERR_INVALID_ARG, "training PSNR: no frame started");
  double sum = 0;
  for (int v : views) {
    if (v < 0 || v >= views_->size()) {
      return Status(M4D_ERR_INVALID_ARG, "training PSNR: no such view");
    }
    double view_psnr = 0;
    M4D_RETURN_IF_ERROR(ViewPsnr(dynamic_set, v, &view_psnr));
    sum += view_psnr;
  }
  *psnr = sum / std::max<size_t>(1, views.size());
  return Status::Ok();
}

Status TrainingPsnrMeter::ViewPsnr(const GaussianSet& dynamic_set, int v, double* psnr) {
  RenderSettings focused = settings_;
  focused.focus_layer = 1;
  focused.focus_margin = 0;  // the tiles around hold the static render, as measured
  const M4dGaussians layers[2] = {GaussianView(static_set_), GaussianView(dynamic_set)};
  const Camera& camera = views_->cameras[v];
  const ProjectedSplats* projection = nullptr;
  M4D_RETURN_IF_ERROR(static_views_->Projection(v, camera, &projection));
  M4D_RETURN_IF_ERROR(RenderForward(camera, layers, 2, focused, nullptr, projection, &context_));
  const TileFocus& focus = context_.focus;
  TileErrors(context_.color.data(), views_->images[v], focus.tiles_x, focus.tiles_y, &errors_);
  double error = 0;
  for (size_t t = 0; t < errors_.size(); ++t) {
    error += focus.rendered(t) ? errors_[t] : static_error_[v][t];
  }
  *psnr = PsnrFromSquaredError(error, views_->images[v].pixels.size());
  return Status::Ok();
}

}  // namespace m4d
