// Where a view changed between two frames by more than its sensor noise explains: the test video
// codecs make before they spend motion on a block. Real captures differ everywhere from frame to
// frame (sensor noise and compression, even where no person is:
// docs/results/2026-11-30-comment-measurements.md), so a Gaussian that "moves" in the lookahead
// where the images did not change has fitted noise or an under-constrained direction, not motion.
//
// Per pixel d = mean over channels of |after - before|, box-averaged over a square of side
// 2 * radius + 1 (noise averages out, motion does not). The noise level is the median of the
// averaged d over the view (most of a view is static); a pixel changed when its averaged d
// exceeds max(min_difference, noise_multiple x that median). The mask is then dilated by
// `radius` so the Gaussians at a moving edge see it.
#ifndef M4D_ENCODER_DECOUPLING_TEMPORAL_CHANGE_H_
#define M4D_ENCODER_DECOUPLING_TEMPORAL_CHANGE_H_

#include <vector>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct TemporalChangeOptions {
  int radius = 2;
  float noise_multiple = 4.0f;
  // In [0, 1] colour units: 8/255, above JPEG's and a flicker's few levels, below a person
  // against a wall (tens of levels).
  float min_difference = 0.03f;
};

struct TemporalChange {
  std::vector<float> mask;  // per pixel, row-major: 1 changed, 0 not
  float noise_level = 0;    // the median averaged difference
  float changed_share = 0;  // fraction of pixels changed (after dilation)
};

// M4D_ERR_INVALID_ARG when the images differ in size or are not RGB, or for bad options.
Status MeasureTemporalChange(const Image& before, const Image& after,
                             const TemporalChangeOptions& options, TemporalChange* change);

}  // namespace m4d

#endif  // M4D_ENCODER_DECOUPLING_TEMPORAL_CHANGE_H_
