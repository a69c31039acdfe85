// ViewBatchGradients: the gradients of motion estimation's L_color for one step, the mean over
// the step's training views, with the static layer frozen. With more than one view per step
// and more than one thread, the views are rendered at once, one per thread: a render of the
// focus tiles alone has too few tiles to keep two cores busy, and the steps between renders
// (binning, the loss) run on one. Each view's gradients are kept apart and summed in the
// batch's order, so the result does not depend on the thread count.
#ifndef M4D_ENCODER_MOTION_VIEW_BATCH_GRADIENTS_H_
#define M4D_ENCODER_MOTION_VIEW_BATCH_GRADIENTS_H_

#include <memory>
#include <vector>

#include "encoder/src/metrics/focused_loss.h"
#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/train/frozen_layer_views.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/layers/gaussian_views.h"

namespace m4d {

struct ViewBatchResult {
  // Mean over the batch of dL_color/d(position), d(rotation) (3 and 4 per dynamic Gaussian)
  // and d(SH DC) (3 per Gaussian, when asked for).
  std::vector<float> positions, rotations, dc;
  std::vector<double> losses;  // L_color of each view, in batch order
};

class ViewBatchGradients {
 public:
  // settings.threads is the threads to use in all (0: the hardware's); the static layer's
  // projection and render per view come from static_views, which must outlive this object.
  // Only the tiles the dynamic splats reach are rendered, without a margin: the loss reads
  // the tiles around them from the static layer's render (metrics/focused_loss.h).
  ViewBatchGradients(const TrainingViews& views, const RenderSettings& settings, double ssim_weight,
                     FrozenLayerViews* static_views);
  ~ViewBatchGradients();

  // Renders layers (static, then the moved dynamic set) from each view of `batch` and sums
  // their gradients into *result; with_dc also sums the SH DC gradients.
  Status Compute(const M4dGaussians layers[2], const std::vector<int>& batch, bool with_dc,
                 ViewBatchResult* result);

  // The threads this object runs on, for the step's other parallel work.
  ThreadPool* pool() { return pool_.get(); }

 private:
  struct Slot;
  Status RenderView(int view, const M4dGaussians layers[2], int threads, Slot* slot);

  const TrainingViews& views_;
  RenderSettings settings_;
  double ssim_weight_;
  FrozenLayerViews* static_views_;
  std::unique_ptr<ThreadPool> pool_;
  std::vector<std::unique_ptr<Slot>> slots_;  // one per view of the batch
};

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_VIEW_BATCH_GRADIENTS_H_
