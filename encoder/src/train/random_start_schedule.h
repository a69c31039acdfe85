// The schedule a keyframe trains with when it starts from random points (random_start.h).
// The reference's rates suit points that structure from motion put on surfaces. Random points
// stand anywhere in the cameras' box, and at those rates a short run moves them too little to
// reach the surfaces. With adaptive density control, such a start trains with faster position
// and scale rates and skips the opacity reset, which would cull the Gaussians still on their way
// (docs/results/2026-11-29-random-start-schedule.md). MCMC, built for random starts, keeps its
// schedule.
#ifndef M4D_ENCODER_TRAIN_RANDOM_START_SCHEDULE_H_
#define M4D_ENCODER_TRAIN_RANDOM_START_SCHEDULE_H_

#include <vector>

#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"

namespace m4d {

struct RandomStartSchedule {
  float position_rate = 4.0f;  // the position rate's decay, start and end, times this
  float scaling_rate = 4.0f;   // the scale rate times this
  bool opacity_reset = false;
};

// Whether a keyframe trained with `options` from `starts` (InitialKeyframeModel's) takes the
// random start's schedule: adaptive density control after points drawn at random (the chain's
// last resort, or options.random_initialisation).
bool TakesRandomStartSchedule(const KeyframeTrainingOptions& options,
                              const std::vector<KeyframeStart>& starts);

// The options a keyframe trains with from `starts`: `options`, with `schedule` applied where it
// takes the random start's.
KeyframeTrainingOptions OptionsForStart(const KeyframeTrainingOptions& options,
                                        const std::vector<KeyframeStart>& starts,
                                        const RandomStartSchedule& schedule = {});

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_RANDOM_START_SCHEDULE_H_
