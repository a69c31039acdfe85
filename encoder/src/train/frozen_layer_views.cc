#include "encoder/src/train/frozen_layer_views.h"

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_renderer.h"

namespace m4d {

FrozenLayerViews::FrozenLayerViews(const M4dGaussians& layer, const RenderSettings& settings,
                                   int view_count)
    : layer_(layer),
      settings_(settings),
      projections_(static_cast<size_t>(view_count)),
      projected_(static_cast<size_t>(view_count), false),
      renders_(static_cast<size_t>(view_count)) {
  settings_.focus_layer = -1;
  settings_.blend_weights = false;
}

Status FrozenLayerViews::CheckView(int view) const {
  if (view < 0 || static_cast<size_t>(view) >= projections_.size()) {
    return Status(M4D_ERR_INVALID_ARG, "frozen layer views: view out of range");
  }
  return Status::Ok();
}

Status FrozenLayerViews::Projection(int view, const Camera& camera,
                                    const ProjectedSplats** projection) {
  M4D_RETURN_IF_ERROR(CheckView(view));
  if (!projected_[view]) {
    M4D_RETURN_IF_ERROR(ProjectLayer(camera, layer_, settings_.sh_degree, &projections_[view]));
    projected_[view] = true;
  }
  *projection = &projections_[view];
  return Status::Ok();
}

Status FrozenLayerViews::Render(int view, const Camera& camera, const Image** render) {
  M4D_RETURN_IF_ERROR(CheckView(view));
  Image& image = renders_[view];
  if (image.pixels.empty()) {
    const ProjectedSplats* projection = nullptr;
    M4D_RETURN_IF_ERROR(Projection(view, camera, &projection));
    RenderContext context;
    M4D_RETURN_IF_ERROR(
        RenderForward(camera, &layer_, 1, settings_, nullptr, projection, &context));
    image = Image(camera.width, camera.height, 3);
    image.pixels = std::move(context.color);
  }
  *render = &image;
  return Status::Ok();
}

}  // namespace m4d
