// The options of each stage the encoder runs on a frame, and of its stream writer and renders,
// from the EncoderOptions: each stage gets the stream's SH degree, background and threads, and a
// seed of its own per frame, so that no two stages or frames draw the same random numbers.
#ifndef M4D_ENCODER_PIPELINE_STAGE_OPTIONS_H_
#define M4D_ENCODER_PIPELINE_STAGE_OPTIONS_H_

#include <cstddef>

#include "encoder/src/capture/capture.h"
#include "encoder/src/compensation/compensation_training.h"
#include "encoder/src/decoupling/lookahead_decoupling.h"
#include "encoder/src/motion/motion_estimation.h"
#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/stream/stream_writer.h"
#include "encoder/src/train/keyframe_trainer.h"

namespace m4d {

// The training of a keyframe from scratch: options.keyframe with the stream's SH degree,
// quantization, background, threads and seed.
KeyframeTrainingOptions FirstKeyframeTraining(const EncoderOptions& options);

// The keyframe schedule shortened to options.retrain_iterations for a restart at `frame`; the
// model's first `frozen` Gaussians (a dependent GOP's static set) stay as they are.
KeyframeTrainingOptions RetrainingOptions(const EncoderOptions& options, int frame, size_t frozen);

// The lookahead decoupling of the keyframe of `frame`.
DecouplingOptions KeyframeDecoupling(const EncoderOptions& options, int frame);

// The motion estimation of inter frame `frame`, `length` frames after its keyframe, over
// `view_count` training views; the GOP's first estimation also trains the MLP (train_mlp).
MotionEstimationOptions FrameMotionOptions(const EncoderOptions& options, int frame, int length,
                                           bool train_mlp, int view_count);

// The compensation training of inter frame `frame` in a scene of this extent.
CompensationOptions FrameCompensationOptions(const EncoderOptions& options, int frame,
                                             float scene_extent);

// The writer of a stream of `frames` frames of the capture.
StreamWriterOptions WriterOptions(const EncoderOptions& options, int frames,
                                  const Capture& capture);

// The renders that measure frames: the stream's SH degree and background.
RenderSettings EncoderRenderSettings(const EncoderOptions& options);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_STAGE_OPTIONS_H_
