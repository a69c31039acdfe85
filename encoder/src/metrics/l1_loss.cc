#include "encoder/src/metrics/l1_loss.h"

#include <cmath>
#include <cstddef>

namespace m4d {

Status L1Loss(const Image& rendered, const Image& target, double* loss, Image* grad) {
  M4D_RETURN_IF_ERROR(CheckSameShape(rendered, target, "l1 loss"));
  const size_t n = rendered.pixels.size();
  const float* __restrict r = rendered.pixels.data();
  const float* __restrict t = target.pixels.data();
  // Four partial sums in double: the loop vectorizes without reordering any one sum.
  double lanes[4] = {0, 0, 0, 0};
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    for (int j = 0; j < 4; ++j) lanes[j] += std::fabs(static_cast<double>(r[i + j]) - t[i + j]);
  }
  for (; i < n; ++i) lanes[0] += std::fabs(static_cast<double>(r[i]) - t[i]);
  *loss = (lanes[0] + lanes[1] + lanes[2] + lanes[3]) / static_cast<double>(n);
  if (!grad) return Status::Ok();
  Reshape(rendered.width, rendered.height, rendered.channels, grad);
  const float step = static_cast<float>(1.0 / static_cast<double>(n));
  float* g = grad->pixels.data();
  for (i = 0; i < n; ++i) g[i] = r[i] > t[i] ? step : (r[i] < t[i] ? -step : 0.0f);
  return Status::Ok();
}

}  // namespace m4d
