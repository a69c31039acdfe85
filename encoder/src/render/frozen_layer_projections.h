// FrozenLayerProjections: one layer's projection per training view, made on first use.
// Motion estimation and compensation render the frozen static layer from the same views
// hundreds of times per frame; projecting its tens of thousands of Gaussians was a fifth of
// each step. The renders are identical (RenderForward with first_layer, splat_renderer.h).
#ifndef M4D_ENCODER_RENDER_FROZEN_LAYER_PROJECTIONS_H_
#define M4D_ENCODER_RENDER_FROZEN_LAYER_PROJECTIONS_H_

#include <vector>

#include "common/status.h"
#include "render/camera.h"
#include "render/gaussian_layer_view.h"
#include "render/projected_splats.h"

namespace m4d {

class FrozenLayerProjections {
 public:
  // `layer`'s arrays must stay unchanged while this object is used.
  FrozenLayerProjections(const GaussianLayerView& layer, int sh_degree, int view_count);

  // The layer's projection for view `view` (index below view_count) seen by `camera`: made
  // on the first call for that view, the same object after. Fails as ProjectLayer does.
  Status For(int view, const Camera& camera, const ProjectedSplats** projection);

 private:
  GaussianLayerView layer_;
  int sh_degree_;
  std::vector<ProjectedSplats> projections_;
  std::vector<bool> made_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_RENDER_FROZEN_LAYER_PROJECTIONS_H_
