// Backward of the per-tile blending: for each pixel group of a tile, replay the forward walk
// (the SDK's BlendPixelGroup, so every alpha and every skip decision is recomputed bit for
// bit; this file is compiled without floating-point contraction for that), check that it
// ends where the forward pass ended, then walk the blended splats back to front with the
// exact transmittances and accumulate, per tile entry, the gradients of the splat's 2D
// quantities; at the end of the tile they go to the entries' slots (tile_binning.h).
//
// With C = sum_i c_i alpha_i T_i + T_final bg and A = 1 - T_final, the walk keeps
// R_i = (what lies behind splat i) / T_(i+1), starting from bg, and RA_i likewise for A:
// dC/dalpha_i = T_i (c_i - R_i) and dA/dalpha_i = T_i (1 - RA_i). A clamped alpha (0.99)
// is constant: its splat then gets no gradient through alpha.
#ifndef M4D_ENCODER_RASTER_RASTERIZER_BACKWARD_H_
#define M4D_ENCODER_RASTER_RASTERIZER_BACKWARD_H_

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "encoder/src/raster/tile_binning.h"
#include "encoder/src/raster/tile_splats.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

// Gradients kept per slot, in this order.
enum EntryGradient {
  kGradMeanX,
  kGradMeanY,
  kGradConicA,
  kGradConicB,
  kGradConicC,
  kGradOpacity,
  kGradColorR,
  kGradColorG,
  kGradColorB,
  kEntryGradients
};

// The splats one pixel group blended, front to back, with their alphas and transmittances.
// Per-worker storage, reserved before a parallel section so that workers never allocate.
class BlendRecord {
 public:
  static constexpr size_t kLaneBytes = 8 * sizeof(float);

  void Reserve(size_t max_splats);
  void Clear() { size_ = 0; }
  size_t size() const { return size_; }
  // alpha and transmittance: 8 lanes each. Kept only if `keep` (written either way, so
  // that the caller needs no branch).
  void Push(uint32_t splat, const void* alpha, const void* transmittance, bool keep) {
    splat_[size_] = splat;
    std::memcpy(&lanes_[16 * size_], alpha, kLaneBytes);
    std::memcpy(&lanes_[16 * size_ + 8], transmittance, kLaneBytes);
    size_ += keep ? 1 : 0;
  }
  uint32_t splat(size_t h) const { return splat_[h]; }
  // Per tile entry: 1 when its splat is trained (scratch of BackpropagateTile).
  uint8_t* trainable() { return trainable_.data(); }
  const float* alpha(size_t h) const { return &lanes_[16 * h]; }
  const float* transmittance(size_t h) const { return &lanes_[16 * h + 8]; }

 private:
  size_t size_ = 0;
  std::vector<uint32_t> splat_;
  std::vector<float> lanes_;  // per splat: 8 alphas, 8 transmittances
  std::vector<uint8_t> trainable_;
};

struct TileGradientTarget {
  int width = 0, height = 0;
  const float* background = nullptr;
  const float* dl_dcolor = nullptr;  // width * height * 3
  const float* dl_dalpha = nullptr;  // width * height, or null
  const float* final_transmittance = nullptr;
  const uint32_t* last_contributor = nullptr;
  float* slot_gradients = nullptr;  // kEntryGradients per slot
  // Splats of a lower index (the leading frozen layers) get no gradient and their slots are
  // not written: a tile without a trained splat is skipped, and so is every pixel group that
  // blended none. The trained splats' gradients are the same bit for bit.
  uint32_t first_trainable = 0;
};

// Writes the gradients of every entry of `tile` to its slot, using accumulator (per-worker
// scratch of kEntryGradients * bins.max_tile_entries floats). Returns false if the replay of
// a pixel did not reproduce the forward pass's final transmittance and last contributor.
bool BackpropagateTile(const ProjectedSplats& splats, const TileBins& bins, size_t tile,
                       const TileGradientTarget& target, TileSplatBuffer* buffer,
                       BlendRecord* record, float* accumulator);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_RASTERIZER_BACKWARD_H_
