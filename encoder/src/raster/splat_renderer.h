// The SDK's reference renderer and the encoder's training forward pass: a CPU tile-based
// 3D Gaussian splatting rasterizer with the conventions of the reference 3DGS implementation
// (see splat_projection.h for preprocessing, splat_alpha.h and pixel_group_blend.h for
// blending, camera.h for the pixel grid).
//
// Work is spread over a persistent pool of threads: preprocessing over Gaussians, blending
// over 16x16 tiles. The result does not depend on the thread count.
#ifndef M4D_ENCODER_RASTER_SPLAT_RENDERER_H_
#define M4D_ENCODER_RASTER_SPLAT_RENDERER_H_

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/render_settings.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

// Renders layers[0..layer_count) together (Gaussians indexed globally in concatenation
// order) into context: colour, alpha and per-Gaussian projection results, plus, when
// settings.blend_weights, each Gaussian's blend weight, and when error_image (width * height
// floats) is not null, each Gaussian's error-weighted blend weight. With settings.focus_layer
// only the focus tiles are rendered (tile_focus.h; context->focus says which), and a backward
// pass needs the layers before focus_layer frozen. Fails with
// M4D_ERR_INVALID_ARG for a null context, a bad camera (ValidateCamera), a bad setting or an
// inconsistent layer (null arrays, SH degree above 3), M4D_ERR_LIMIT beyond
// kMaxRenderGaussians Gaussians or kMaxTileEntries (splat, tile) pairs, M4D_ERR_NOMEM when
// memory runs out. Gaussians with non-finite values are culled.
Status RenderForward(const Camera& camera, const M4dGaussians* layers, int layer_count,
                     const RenderSettings& settings, const float* error_image,
                     RenderContext* context);

// The same render, with layer 0's projection given: `first_layer` must be what ProjectLayer
// made of layers[0] for this camera and settings.sh_degree (M4D_ERR_INVALID_ARG if its size
// differs). Training renders a frozen layer (the static one, under motion estimation and
// compensation) from the same views many times; it is projected once per view instead of
// once per render. The result is identical.
Status RenderForward(const Camera& camera, const M4dGaussians* layers, int layer_count,
                     const RenderSettings& settings, const float* error_image,
                     const ProjectedSplats* first_layer, RenderContext* context);

// Projects `layer` alone as RenderForward projects its first layer, on the calling thread.
// Fails as RenderForward does for a bad camera, SH degree or layer.
Status ProjectLayer(const Camera& camera, const M4dGaussians& layer, int sh_degree,
                    ProjectedSplats* out);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_SPLAT_RENDERER_H_
