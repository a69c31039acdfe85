#include "encoder/src/export/frame_gaussians.h"

#include <algorithm>

#include "sdk/src/layers/gaussian_views.h"

namespace m4d {
Status GaussianSetFromFrame(const M4dFrame& frame, uint32_t layers, GaussianSet* out) {
  *out = GaussianSet();
  const bool with_static = (layers & M4D_LAYER_STATIC) != 0;
  const bool with_dynamic = (layers & M4D_LAYER_DYNAMIC) != 0;
  out->sh_degree = static_cast<int>(std::max(with_static ? frame.static_layer.sh_degree : 0u,
                                             with_dynamic ? frame.dynamic_layer.sh_degree : 0u));
  if (with_static) M4D_RETURN_IF_ERROR(AppendLayer(frame.static_layer, out));
  if (with_dynamic) M4D_RETURN_IF_ERROR(AppendLayer(frame.dynamic_layer, out));
  return Status::Ok();
}

}  // namespace m4d
