// The motion mode decision (ours): an inter frame codes its estimated motion only if that raises
// the training views' mean PSNR by more than EncoderOptions::motion_min_gain above showing the
// previous frame again. On real captures the motion of an over-dynamic keyframe can make a
// frame worse than doing nothing (docs/results/2026-11-30-comment-measurements.md); a skipped
// frame codes SkipMotion's grid.
#ifndef M4D_ENCODER_PIPELINE_MOTION_DECISION_H_
#define M4D_ENCODER_PIPELINE_MOTION_DECISION_H_

#include "encoder/src/pipeline/training_psnr_meter.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

struct MotionDecision {
  double gain = 0;    // training PSNR of the moved set minus the unmoved one's (dB)
  bool skip = false;  // not above the minimum gain: the frame codes no motion
};

// Measures `still` (the last frame's dynamic set) and `moved` (it with the frame's motion) with
// the meter, which has started the frame.
Status DecideMotion(const GaussianSet& still, const GaussianSet& moved, double min_gain,
                    TrainingPsnrMeter* meter, MotionDecision* decision);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_MOTION_DECISION_H_
