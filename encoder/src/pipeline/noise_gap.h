// A keyframe's overfit to its own frame's noise, in dB: its PSNR over the pixels that did not
// change between the GOP's first two frames (temporal_change.h), on its own frame's training
// views minus on the second frame's. A keyframe that fitted sensor noise loses that much on the
// next frame where nothing moved, so the GOP's quality guard (GopPolicy::Restarts) compares
// inter frames with the keyframe's PSNR less this gap, not with what no inter frame can reach.
// 0 on a noise-free capture.
#ifndef M4D_ENCODER_PIPELINE_NOISE_GAP_H_
#define M4D_ENCODER_PIPELINE_NOISE_GAP_H_

#include "encoder/src/capture/capture.h"
#include "encoder/src/decoupling/temporal_change.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// The gap of the keyframe of frame `keyframe` (its decoded static_set and dynamic_set) against
// `next`, the second frame's training views.
Status MeasureNoiseGap(const Capture& capture, int keyframe, const GaussianSet& static_set,
                       const GaussianSet& dynamic_set, const TrainingViews& next,
                       const TemporalChangeOptions& change, const RenderSettings& settings,
                       double* gap);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_NOISE_GAP_H_
