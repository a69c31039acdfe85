#include "encoder/src/raster/rasterizer_backward.h"

#include <algorithm>

#include "encoder/src/raster/lane_sums.h"
#include "encoder/src/raster/pixel_group_blend.h"
#include "sdk/src/render/lanes.h"
#include "sdk/src/render/projection_constants.h"
#include "sdk/src/render/splat_alpha.h"

namespace m4d {

void BlendRecord::Reserve(size_t max_splats) {
  if (splat_.size() >= max_splats && !splat_.empty()) return;
  const size_t n = std::max<size_t>(max_splats, 1);
  splat_.resize(n);
  lanes_.resize(2 * kLanes * n);
  trainable_.resize(n);
}

namespace {

// Per-lane dL/dC and dL/dA of a pixel group (zero outside the image).
struct GroupLoss {
  Lanes color[3];
  Lanes alpha;
};

GroupLoss LoadGroupLoss(const TileGradientTarget& target, const PixelGroup& g) {
  GroupLoss loss = {{Lanes{}, Lanes{}, Lanes{}}, Lanes{}};
  const size_t row = static_cast<size_t>(g.y) * target.width;
  for (int l = 0; l < kLanes && g.x0 + l < target.width; ++l) {
    const size_t p = row + g.x0 + l;
    for (int c = 0; c < 3; ++c) loss.color[c][l] = target.dl_dcolor[3 * p + c];
    if (target.dl_dalpha) loss.alpha[l] = target.dl_dalpha[p];
  }
  return loss;
}

bool MatchesForward(const TileGradientTarget& target, const PixelGroup& g) {
  const size_t row = static_cast<size_t>(g.y) * target.width;
  for (int l = 0; l < kLanes && g.x0 + l < target.width; ++l) {
    const size_t p = row + g.x0 + l;
    if (g.transmittance[l] != target.final_transmittance[p] ||
        static_cast<uint32_t>(g.last[l]) != target.last_contributor[p]) {
      return false;
    }
  }
  return true;
}

// Walks the recorded splats of group g back to front, adding to their entry gradients.
// Splats not `trainable` (null: all are) only pass on what lies behind them.
void WalkBack(const TileSplats& s, const PixelGroup& g, const BlendRecord& record,
              const uint8_t* trainable, const GroupLoss& loss, const float* background,
              float* entry_gradients) {
  Lanes behind[3] = {Broadcast(background[0]), Broadcast(background[1]), Broadcast(background[2])};
  Lanes behind_alpha{};
  for (size_t h = record.size(); h-- > 0;) {
    const size_t j = record.splat(h);
    const Lanes alpha = LoadLanes(record.alpha(h));
    const Lanes t = LoadLanes(record.transmittance(h));
    const Lanes one_minus = 1.0f - alpha;
    if (trainable && !trainable[j]) {
      behind_alpha = alpha + one_minus * behind_alpha;
      for (int c = 0; c < 3; ++c) behind[c] = alpha * s.color[c][j] + one_minus * behind[c];
      continue;
    }
    Lanes dl_dalpha = loss.alpha * (1.0f - behind_alpha);
    behind_alpha = alpha + one_minus * behind_alpha;
    const Lanes weight = alpha * t;
    Lanes terms[8];  // summed over lanes below
    for (int c = 0; c < 3; ++c) {
      const float colour = s.color[c][j];
      dl_dalpha += loss.color[c] * (colour - behind[c]);
      behind[c] = alpha * colour + one_minus * behind[c];
      terms[3 + c] = loss.color[c] * weight;
    }
    // Lanes not blended (alpha 0) and clamped alphas pass nothing to opacity and shape.
    const LaneMask live = (alpha > 0.0f) & (alpha < kMaxAlpha);
    const Lanes dl_dpower = live ? dl_dalpha * t * alpha : Lanes{};  // dalpha/dpower = alpha
    const Lanes dx = s.mean_x[j] - g.px;
    terms[0] = dl_dpower;
    terms[1] = dl_dpower * dx;
    terms[2] = terms[1] * dx;
    terms[6] = terms[7] = Lanes{};
    const Lanes sums = LaneSums8(terms);
    // power = -0.5 (a dx^2 + c dy^2) - b dx dy, dx = mean x - pixel x; alpha = o exp(power).
    const float a = s.conic_a[j], b = s.conic_b[j], c = s.conic_c[j];
    const float dy = s.mean_y[j] - g.py;
    float* grad = entry_gradients + kEntryGradients * j;
    grad[kGradMeanX] -= a * sums[1] + b * dy * sums[0];
    grad[kGradMeanY] -= c * dy * sums[0] + b * sums[1];
    grad[kGradConicA] -= 0.5f * sums[2];
    grad[kGradConicB] -= dy * sums[1];
    grad[kGradConicC] -= 0.5f * dy * dy * sums[0];
    grad[kGradOpacity] += sums[0] / s.opacity[j];
    for (int k = 0; k < 3; ++k) grad[kGradColorR + k] += sums[3 + k];
  }
}

}  // namespace

bool BackpropagateTile(const ProjectedSplats& splats, const TileBins& bins, size_t tile,
                       const TileGradientTarget& target, TileSplatBuffer* buffer,
                       BlendRecord* record, float* accumulator) {
  const uint32_t begin = bins.tile_start[tile], end = bins.tile_start[tile + 1];
  const uint32_t* entries = bins.entries.data() + begin;
  uint8_t* trainable = nullptr;
  if (target.first_trainable > 0) {
    trainable = record->trainable();
    bool any = false;
    for (uint32_t j = 0; j < end - begin; ++j) {
      trainable[j] = entries[j] >= target.first_trainable;
      any = any || trainable[j];
    }
    if (!any) return true;
  }
  const TileSplats& s = buffer->Gather(splats, entries, end - begin);
  std::fill(accumulator, accumulator + kEntryGradients * size_t{end - begin}, 0.0f);
  const int tx = static_cast<int>(tile % bins.tiles_x), ty = static_cast<int>(tile / bins.tiles_x);
  const int x_end = std::min(target.width, (tx + 1) * kTileSize);
  const int y_end = std::min(target.height, (ty + 1) * kTileSize);
  bool matches = true;
  for (int y = ty * kTileSize; y < y_end; ++y) {
    for (int x0 = tx * kTileSize; x0 < x_end; x0 += kLanes) {
      PixelGroup group = StartPixelGroup(x0, y, target.width);
      record->Clear();
      bool trained = !trainable;
      BlendPixelGroup(s, &group, [&](size_t j, const Lanes& alpha, const Lanes& t, bool blended) {
        record->Push(static_cast<uint32_t>(j), &alpha, &t, blended);
        trained = trained || (blended && trainable[j]);
      });
      matches = matches && MatchesForward(target, group);
      if (!trained) continue;
      WalkBack(s, group, *record, trainable, LoadGroupLoss(target, group), target.background,
               accumulator);
    }
  }
  for (uint32_t j = 0; j < end - begin; ++j) {
    if (trainable && !trainable[j]) continue;
    std::copy(accumulator + kEntryGradients * j, accumulator + kEntryGradients * (j + 1),
              target.slot_gradients + kEntryGradients * size_t{bins.entry_slot[begin + j]});
  }
  return matches;
}

}  // namespace m4d
