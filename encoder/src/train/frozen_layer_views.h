// FrozenLayerViews: what a frozen layer looks like from each training view, made on first use:
// its projection, and its render alone. Motion estimation and compensation train the dynamic
// layer over the static one, which does not change within a frame, from the same views
// hundreds of times per frame:
// - projecting its tens of thousands of Gaussians was a fifth of each step; a render given the
//   projection (RenderForward with first_layer, splat_renderer.h) is the same render;
// - a focused render (tile_focus.h) leaves out the tiles the trained layers do not reach,
//   which hold exactly this layer's render alone, so the loss can read them from here.
#ifndef M4D_ENCODER_TRAIN_FROZEN_LAYER_VIEWS_H_
#define M4D_ENCODER_TRAIN_FROZEN_LAYER_VIEWS_H_

#include <vector>

#include "encoder/src/image/image.h"
#include "encoder/src/raster/render_settings.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

class FrozenLayerViews {
 public:
  // `layer`'s arrays must stay unchanged while this object is used; settings are those of the
  // renders it joins (SH degree, background, threads; no focus).
  FrozenLayerViews(const M4dGaussians& layer, const RenderSettings& settings, int view_count);

  // The layer's projection for view `view` (index below view_count) seen by `camera`: made
  // on the first call for that view, the same object after. Fails as ProjectLayer does.
  Status Projection(int view, const Camera& camera, const ProjectedSplats** projection);

  // The layer's render alone (RGB, not clamped) for that view. Fails as RenderForward does.
  Status Render(int view, const Camera& camera, const Image** render);

 private:
  Status CheckView(int view) const;

  M4dGaussians layer_;
  RenderSettings settings_;
  std::vector<ProjectedSplats> projections_;
  std::vector<bool> projected_;
  std::vector<Image> renders_;  // empty until made
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_FROZEN_LAYER_VIEWS_H_
