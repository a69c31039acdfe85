#include "encoder/src/decoupling/temporal_change.h"

#include <algorithm>
#include <cmath>

namespace m4d {
namespace {

// Separable box average of a width x height plane, clamped at the borders.
std::vector<float> BoxAverage(const std::vector<float>& in, int width, int height, int radius) {
  std::vector<float> rows(in.size()), out(in.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      int count = 0;
      for (int k = std::max(0, x - radius); k <= std::min(width - 1, x + radius); ++k, ++count) {
        sum += in[static_cast<size_t>(y) * width + k];
      }
      rows[static_cast<size_t>(y) * width + x] = sum / static_cast<float>(count);
    }
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float sum = 0;
      int count = 0;
      for (int k = std::max(0, y - radius); k <= std::min(height - 1, y + radius); ++k, ++count) {
        sum += rows[static_cast<size_t>(k) * width + x];
      }
      out[static_cast<size_t>(y) * width + x] = sum / static_cast<float>(count);
    }
  }
  return out;
}

}  // namespace

Status MeasureTemporalChange(const Image& before, const Image& after,
                             const TemporalChangeOptions& options, TemporalChange* change) {
  if (before.channels != 3 || after.channels != 3 || before.width != after.width ||
      before.height != after.height || before.pixels.empty()) {
    return Status(M4D_ERR_INVALID_ARG, "temporal change: images must be RGB of one size");
  }
  if (options.radius < 0 || options.radius > 64 || !(options.noise_multiple >= 0) ||
      !(options.min_difference >= 0)) {
    return Status(M4D_ERR_INVALID_ARG, "temporal change: bad options");
  }
  const int w = before.width, h = before.height;
  const size_t n = static_cast<size_t>(w) * h;
  std::vector<float> d(n);
  for (size_t p = 0; p < n; ++p) {
    float sum = 0;
    for (int c = 0; c < 3; ++c)
      sum += std::fabs(after.pixels[3 * p + c] - before.pixels[3 * p + c]);
    d[p] = sum / 3.0f;
  }
  const std::vector<float> averaged = BoxAverage(d, w, h, options.radius);
  std::vector<float> sorted = averaged;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  change->noise_level = sorted[n / 2];
  const float threshold =
      std::max(options.min_difference, options.noise_multiple * change->noise_level);
  for (size_t p = 0; p < n; ++p) d[p] = averaged[p] > threshold ? 1.0f : 0.0f;
  // Dilation: any changed pixel within the square makes the average positive.
  change->mask = BoxAverage(d, w, h, options.radius);
  size_t changed = 0;
  for (float& m : change->mask) {
    m = m > 0 ? 1.0f : 0.0f;
    changed += m > 0 ? 1 : 0;
  }
  change->changed_share = static_cast<float>(changed) / static_cast<float>(n);
  return Status::Ok();
}

}  // namespace m4d
