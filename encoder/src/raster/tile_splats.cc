#include "encoder/src/raster/tile_splats.h"

#include "sdk/src/render/lanes.h"

namespace m4d {

void TileSplatBuffer::Reserve(size_t max_entries) {
  const size_t padded = (max_entries + kLanes - 1) / kLanes * kLanes;
  if (padded <= capacity_ && !storage_.empty()) return;
  capacity_ = padded > capacity_ ? padded : capacity_;
  storage_.assign(kFields * capacity_ + kLanes, 0.0f);
}

const TileSplats& TileSplatBuffer::Gather(const ProjectedSplats& splats, const uint32_t* entries,
                                          size_t n) {
  float* field[kFields];
  for (int f = 0; f < kFields; ++f) field[f] = storage_.data() + f * capacity_;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t g = entries[k];
    field[0][k] = splats.mean_x[g];
    field[1][k] = splats.mean_y[g];
    field[2][k] = splats.extent_x[g];
    field[3][k] = splats.extent_y[g];
    field[4][k] = splats.conic_a[g];
    field[5][k] = splats.conic_b[g];
    field[6][k] = splats.conic_c[g];
    field[7][k] = splats.opacity[g];
    field[8][k] = splats.color[0][g];
    field[9][k] = splats.color[1][g];
    field[10][k] = splats.color[2][g];
  }
  const size_t padded = (n + kLanes - 1) / kLanes * kLanes;
  for (size_t k = n; k < padded; ++k) {
    for (int f = 0; f < kFields; ++f) field[f][k] = 0.0f;
    field[2][k] = field[3][k] = -1.0f;
  }
  view_.count = padded;
  view_.mean_x = field[0];
  view_.mean_y = field[1];
  view_.extent_x = field[2];
  view_.extent_y = field[3];
  view_.conic_a = field[4];
  view_.conic_b = field[5];
  view_.conic_c = field[6];
  view_.opacity = field[7];
  for (int c = 0; c < 3; ++c) view_.color[c] = field[8 + c];
  return view_;
}

}  // namespace m4d
