#include "render/frozen_layer_projections.h"

#include "render/splat_renderer.h"

namespace m4d {

FrozenLayerProjections::FrozenLayerProjections(const GaussianLayerView& layer, int sh_degree,
                                               int view_count)
    : layer_(layer),
      sh_degree_(sh_degree),
      projections_(static_cast<size_t>(view_count)),
      made_(static_cast<size_t>(view_count), false) {}

Status FrozenLayerProjections::For(int view, const Camera& camera,
                                   const ProjectedSplats** projection) {
  if (view < 0 || static_cast<size_t>(view) >= projections_.size()) {
    return Status(M4D_ERR_INVALID_ARG, "frozen layer projections: view out of range");
  }
  if (!made_[view]) {
    M4D_RETURN_IF_ERROR(ProjectLayer(camera, layer_, sh_degree_, &projections_[view]));
    made_[view] = true;
  }
  *projection = &projections_[view];
  return Status::Ok();
}

}  // namespace m4d
