// ProjectedSplats: per Gaussian (global index), what preprocessing computes for the
// rasterizer, as structure of arrays. Culled Gaussians have radius 0 and zero fields.
#ifndef M4D_SDK_RENDER_PROJECTED_SPLATS_H_
#define M4D_SDK_RENDER_PROJECTED_SPLATS_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace m4d {

struct ProjectedSplats {
  std::vector<float> mean_x, mean_y;  // projected mean u, v in pixels (see camera.h)
  std::vector<float> depth;           // camera-space z
  // ceil(3 sqrt(largest eigenvalue of the 2D covariance)) in pixels; 0 when culled. A pixel
  // is evaluated only if its centre lies within this distance of the mean along x and y.
  std::vector<float> radius;
  // Half extents along x and y of where the splat can blend: the radius, or less where its
  // alpha is certainly below 1/255 (see splat_projection.h). Only these pixels are visited.
  std::vector<float> extent_x, extent_y;
  std::vector<float> conic_a, conic_b, conic_c;  // inverse 2D covariance [[a, b], [b, c]]
  std::vector<float> opacity;
  std::vector<float> color[3];         // SH colour + 0.5, clamped at 0
  std::vector<uint8_t> color_clamped;  // bit c set: channel c was clamped (no gradient)
  // Tiles the splat may touch: first column, first row, last column, last row (inclusive).
  std::vector<uint16_t> tile_rect;  // 4 per Gaussian

  size_t size() const { return radius.size(); }
  void Resize(size_t n) {
    for (std::vector<float>* v : {&mean_x, &mean_y, &depth, &radius, &extent_x, &extent_y, &conic_a,
                                  &conic_b, &conic_c, &opacity, &color[0], &color[1], &color[2]}) {
      v->resize(n);
    }
    color_clamped.resize(n);
    tile_rect.resize(4 * n);
  }
  // Copies splats [begin, end) of `from` to the same indices here (sized to hold them).
  void CopyRange(const ProjectedSplats& from, size_t begin, size_t end) {
    std::vector<float> ProjectedSplats::*const fields[] = {
        &ProjectedSplats::mean_x,  &ProjectedSplats::mean_y,   &ProjectedSplats::depth,
        &ProjectedSplats::radius,  &ProjectedSplats::extent_x, &ProjectedSplats::extent_y,
        &ProjectedSplats::conic_a, &ProjectedSplats::conic_b,  &ProjectedSplats::conic_c,
        &ProjectedSplats::opacity};
    for (auto field : fields) {
      std::copy((from.*field).begin() + begin, (from.*field).begin() + end,
                (this->*field).begin() + begin);
    }
    for (int c = 0; c < 3; ++c) {
      std::copy(from.color[c].begin() + begin, from.color[c].begin() + end,
                color[c].begin() + begin);
    }
    std::copy(from.color_clamped.begin() + begin, from.color_clamped.begin() + end,
              color_clamped.begin() + begin);
    std::copy(from.tile_rect.begin() + 4 * begin, from.tile_rect.begin() + 4 * end,
              tile_rect.begin() + 4 * begin);
  }
};

}  // namespace m4d

#endif  // M4D_SDK_RENDER_PROJECTED_SPLATS_H_
