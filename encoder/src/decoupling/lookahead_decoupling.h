// Lookahead motion decoupling (paper sections 3.2 and 4.1): the keyframe model is fine-tuned on
// a later frame t1 with only positions and scales free (count, rotations, opacities and colours
// frozen), the changes and the fine-tuned model's blend-weighted errors are measured
// (lookahead_measures.h), and the classification (motion_classification.h) splits the keyframe
// model - not the fine-tuned one - into its static and dynamic sets.
//
// The lookahead may pass through intermediate frames on its way to t1 (each step fine-tunes
// the previous step's result): gradient steps follow motion of about a splat's size, so a
// single jump to a frame 30 frames on loses fast content, and periodic motion (a swinging
// arm) may be back where it started at t1. Each Gaussian keeps its largest displacement and
// scale change over the steps and its smallest error: a point is a fitting artefact only if
// no step fits it, nor the keyframe model its own frame. (The paper measures the error at t1
// only. Panoptic's thrown ball moves its diameter per frame, farther than gradient steps
// follow, so its error at t1 is high; that rule sent part of it to the static set, where it
// stayed as a ghost.) It also keeps its largest change support: the share of its blend weight
// (keyframe model, each step's cameras) on pixels where the step's images differ from the
// keyframe's beyond the noise (temporal_change.h), less the blend-weighted share of changed
// pixels in those views (what a footprint unrelated to the change would get).
#ifndef M4D_ENCODER_DECOUPLING_LOOKAHEAD_DECOUPLING_H_
#define M4D_ENCODER_DECOUPLING_LOOKAHEAD_DECOUPLING_H_

#include <cstdint>
#include <vector>

#include "encoder/src/decoupling/motion_classification.h"
#include "encoder/src/decoupling/temporal_change.h"
#include "encoder/src/train/encode_context.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct DecouplingOptions {
  int fine_tune_iterations = 100;  // per lookahead step
  TemporalChangeOptions change;    // for DecouplingThresholds::change_support
  // Position rate of the fine-tuning, times the scene extent, decaying tenfold over it (the
  // paper's 5e-4 for its Gaussian optimisations); scales keep the keyframe's rate.
  float position_learning_rate = 5e-4f;
  DecouplingThresholds thresholds;
  EncodeContext context;
};

struct DecouplingResult {
  GaussianModel static_model;
  GaussianModel dynamic_model;
  std::vector<uint8_t> dynamic;  // per Gaussian of the keyframe model
  LookaheadMeasures measures;
  size_t initially_dynamic = 0;  // after the thresholds
  size_t refined_dynamic = 0;    // after the error refinement (before the vote)
};

// keyframe: the trained model of the keyframe; keyframe_views: the keyframe frame's training
// views; steps: the training views of the lookahead's frames in time order, the last being t1
// (at least one), each with the keyframe's cameras in the same order. scene_extent: the
// keyframe training's (for the position learning rate).
Status DecoupleKeyframe(const GaussianModel& keyframe, const TrainingViews& keyframe_views,
                        const std::vector<TrainingViews>& steps, float scene_extent,
                        const DecouplingOptions& options, DecouplingResult* result);

// Splits a model by per-Gaussian flags (1: into `selected`, 0: into `rest`).
void SplitModel(const GaussianModel& model, const std::vector<uint8_t>& flags,
                GaussianModel* selected, GaussianModel* rest);

}  // namespace m4d

#endif  // M4D_ENCODER_DECOUPLING_LOOKAHEAD_DECOUPLING_H_
