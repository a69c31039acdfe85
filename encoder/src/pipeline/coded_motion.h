// An inter frame's motion as the stream carries it. The encoder decides a frame with the
// decoder's own motion code on what the decoder will read, so it needs the rounded grid in the
// writer's form and in the decoder's, and the MLP as the decoder reads it back.
#ifndef M4D_ENCODER_PIPELINE_CODED_MOTION_H_
#define M4D_ENCODER_PIPELINE_CODED_MOTION_H_

#include "encoder/src/layers/motion_grid_writer.h"
#include "encoder/src/motion/motion_estimation.h"
#include "encoder/src/pipeline/encoder_options.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_config.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {

// The MLP as a decoder reads it from the keyframe packet.
Status DecodedMlp(const MlpWeights& mlp, const EncoderOptions& options, MlpWeights* decoded);

// The rounded grid of a motion estimation (null: all zero), dense, in the writer's and the
// decoder's forms.
void DenseGrids(const GridConfig& config, const float* steps, const MotionEstimationResult* motion,
                const GridBox& box, FloatMotionGrid* coded, MotionGrid* decoded);

// A frame without motion: a grid box that no finite position lies in (its lower corner at the
// largest float), so the decoder leaves every Gaussian unchanged (bitstream-spec 6.3, step 1)
// whatever the grid and MLP hold; no voxel is active (every brick zero before 0.10), so the grid
// costs a few bytes.
void SkipMotion(FloatMotionGrid* grid);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_CODED_MOTION_H_
