// The motion rate weight along a GOP. Each inter frame moves the last decoded frame's
// dynamic Gaussians, so the positions a GOP moves drift from where the frame's Gaussians are,
// and the grid needs more bits the later the frame. The 400-step encoder spent them under
// a constant lambda_2 (the default scene's grid grew from 9.7 KB on a GOP's second inter frame
// to 15.6 KB on its ninth); with 130 steps the grid stayed at 9-11 KB. A weight that falls
// along the GOP spends those bits again. Measured with 130 steps, it brought a GOP's middle
// frames closer to the 400-step encoder's for 1-2 % more bytes, but not reliably its last
// frame; 200 steps with the paper's lambda_2 did, so it is off by default
// (docs/results/2026-11-30-readme-notebook.md, "Longer GOPs").
#ifndef M4D_ENCODER_PIPELINE_MOTION_RATE_SCHEDULE_H_
#define M4D_ENCODER_PIPELINE_MOTION_RATE_SCHEDULE_H_

namespace m4d {

// Below this share of lambda_2 the weight falls no further: a long GOP keeps a rate term.
constexpr double kMinMotionRateShare = 0.3;

// The rate weight of a GOP's inter frame `frame_in_gop` (1: the first after the keyframe):
// lambda * max(kMinMotionRateShare, 1 - decay * (frame_in_gop - 1)). decay 0: constant.
double MotionRateWeight(double lambda, int frame_in_gop, double decay);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_MOTION_RATE_SCHEDULE_H_
