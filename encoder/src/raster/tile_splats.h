// TileSplats: the splats of one tile, front to back, gathered into contiguous arrays so that
// eight of them can be tested against a pixel group at once. Padded to a multiple of kLanes
// with entries whose extent is negative, which never touch a pixel.
#ifndef M4D_ENCODER_RASTER_TILE_SPLATS_H_
#define M4D_ENCODER_RASTER_TILE_SPLATS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/render/projected_splats.h"

namespace m4d {

struct TileSplats {
  size_t count = 0;  // padded
  const float* mean_x = nullptr;
  const float* mean_y = nullptr;
  const float* extent_x = nullptr;
  const float* extent_y = nullptr;
  const float* conic_a = nullptr;
  const float* conic_b = nullptr;
  const float* conic_c = nullptr;
  const float* opacity = nullptr;
  const float* color[3] = {nullptr, nullptr, nullptr};
};

// Per-worker storage for one tile's splats. Reserve before a parallel section so that the
// workers never allocate.
class TileSplatBuffer {
 public:
  void Reserve(size_t max_entries);
  // Gathers the splats of entries[0..n) (Gaussian indices, n <= the reserved count).
  const TileSplats& Gather(const ProjectedSplats& splats, const uint32_t* entries, size_t n);

 private:
  static constexpr int kFields = 11;
  size_t capacity_ = 0;  // per field, a multiple of kLanes
  std::vector<float> storage_;
  TileSplats view_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_TILE_SPLATS_H_
