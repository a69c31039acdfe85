// Initial points for a capture that has none (no COLMAP model, no init_pt_cld.npz): a quick
// multi-view estimate (a plane sweep along single rays) instead of points uniform in a box.
// A ray is a random pixel of a random training view; along it, depths are sampled uniformly in
// inverse depth between the near plane and far away, and each depth is scored by how far the
// colours the other views see there are from the pixel's (mean squared difference over the
// views that see the point). The ray gives a point at its best depth only when that depth is
// distinctive: its score well below the ray's median score. A point on a surface looks alike
// from every camera; at a wrong depth it lands on different things. Rays through uniform
// colour (a white wall, a black backdrop) match at every depth and give no point: a global
// "lowest colour variance" choice filled the Panoptic dome's air with points that see white
// wall from everywhere, and trained into fog. Occlusion is ignored: this only has to start
// training near the surfaces.
#ifndef M4D_ENCODER_TRAIN_PHOTO_CONSISTENT_POINTS_H_
#define M4D_ENCODER_TRAIN_PHOTO_CONSISTENT_POINTS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct PhotoConsistencyOptions {
  size_t points = 100000;      // at most this many kept
  int rays_per_point = 3;      // rays drawn per point asked for
  int depths = 48;             // samples along a ray
  float distinctness = 0.35f;  // best score below this times the ray's median score
  // A candidate counts only if this many views see it (the ray's own included; in front of the near
  // plane, inside the image), or half the views when that is fewer. Three, not half: on the
  // Panoptic basketball capture (27 views) a player or the wall near the dome's edge is inside few
  // cameras' frusta; asking half the views gave them no point and training filled them with fog,
  // and two or four views did worse than three on the held-out cameras
  // (docs/results/2026-11-30-readme-notebook.md, "No initial points";
  // docs/results/2026-11-30-comment-measurements.md).
  int min_views = 3;
  // Depth range of the candidates, in multiples of the cameras' extent (scene_extent.h):
  // from the near plane to far_extents times it.
  float far_extents = 50.0f;
  // Per view, per pixel (row-major): rays start only where the mask is positive (null: every
  // pixel). A later keyframe seeds what its prediction does not explain this way.
  const std::vector<std::vector<float>>* ray_masks = nullptr;
  // When bounded, candidates lie inside the world box [box_min, box_max] too. A later
  // keyframe seeds inside the model it grows: its far candidates (up to far_extents) trained
  // into Gaussians 180 units out and 60 wide on the Panoptic basketball capture, whose model
  // spans 12, and stretched the coded position range 15 times.
  bool bounded = false;
  float box_min[3] = {0, 0, 0};
  float box_max[3] = {0, 0, 0};
  uint64_t seed = 0;
  int threads = 0;
};

// M4D_ERR_INVALID_ARG for no views, a zero camera extent, bad options (a box with min above
// max) or masks that do not match the views; the result holds fewer points than asked when fewer
// rays find a distinctive depth (none when the masks are empty).
Status PhotoConsistentPoints(const TrainingViews& views, const PhotoConsistencyOptions& options,
                             PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_PHOTO_CONSISTENT_POINTS_H_
