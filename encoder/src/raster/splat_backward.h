// The rasterizer's backward pass, for training: gradients of a loss with respect to every
// rendered Gaussian's coded values, given dL/dcolour (and optionally dL/dalpha) of the last
// RenderForward (encoder/src/raster/splat_renderer.h) of a context.
//
// Tiles are processed in parallel, each writing the gradients of its own (splat, tile)
// entries; each Gaussian then sums its entries in a fixed order and runs the projection
// backward, in parallel over Gaussians. No atomics; the result does not depend on the
// thread count.
#ifndef M4D_ENCODER_RASTER_SPLAT_BACKWARD_H_
#define M4D_ENCODER_RASTER_SPLAT_BACKWARD_H_

#include <vector>

#include "encoder/src/raster/projection_backward.h"
#include "encoder/src/raster/rasterizer_backward.h"
#include "encoder/src/raster/render_context.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct SplatGradients {
  // One per rendered layer, in order. A layer whose arrays are all null is frozen: it gets no
  // gradients (and costs nothing beyond the blending), e.g. the static set while motion trains.
  const LayerGradients* layers = nullptr;
  int layer_count = 0;
  // Optional, 2 per Gaussian (global index): dL/d(projected mean) in pixels, the view-space
  // gradient of densification (see viewspace_gradient.h for the reference's units). After a
  // focused forward pass (RenderSettings::focus_layer), zero for the layers before the focus
  // layer, as is `color`.
  float* mean2d = nullptr;
  // Optional, 3 per Gaussian (global index): dL/d(the splat's colour) before the clamp and the
  // SH basis. With dL/dcolour 1 everywhere, a splat's blending weight alpha T summed over the
  // view's pixels, for any colour (importance_pruning.h).
  float* color = nullptr;
};

// Scratch of the backward pass, reused between calls.
struct BackwardWorkspace {
  std::vector<float> slot_gradients;             // kEntryGradients per slot
  std::vector<BlendRecord> records;              // per worker
  std::vector<std::vector<float>> accumulators;  // per worker
  std::vector<char> replay_mismatch;             // per worker
};

// dl_dcolor: width * height * 3 (HWC like the colour output); dl_dalpha: width * height or
// null. Overwrites every array of out (culled Gaussians get zeros; SH coefficients beyond the
// active degree get zeros). The layer arrays of the forward pass must be unchanged. Fails
// with M4D_ERR_INVALID_ARG for null arguments, a context without a successful forward pass,
// a layer count that differs from the forward pass's, or null gradient arrays; with
// M4D_ERR_INVALID_ARG also if the replay of the forward pass does not end where the
// forward pass ended (its state was modified); M4D_ERR_NOMEM when memory runs out.
Status RenderBackward(const float* dl_dcolor, const float* dl_dalpha, RenderContext* context,
                      const SplatGradients& out, BackwardWorkspace* workspace);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_SPLAT_BACKWARD_H_
