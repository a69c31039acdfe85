// The rate term of keyframe training: the paper's rate-aware optimisation (section 4.2, there
// for the motion grid) carried to the keyframe's attributes. While training is
// quantization-aware, the loss gains lambda_k times the bits the keyframe coder spends on the
// attributes it codes as plain values (log scales, opacity, SH DC, higher SH), in the motion
// grid's unit of 100 kilobits.
//
// The entropy model is the histogram of each group's quantized values, as the coder's
// (Draco codes a group with one table over its components; the stream carries what it
// needs, so the model costs nothing to send). A value's rate is interpolated between the
// -log2 probabilities of its two nearest levels, so its gradient pulls it towards the more
// probable neighbour, the entropy-constrained quantizer's move; the photometric gradient
// of the quantized value pushes back where the move would show. A learned mixture of
// logistics (the motion grid's model) would cost six exponentials a value every iteration,
// more than the iteration's render at 100k Gaussians, for the same pull.
//
// Positions are left out: they are coded as differences in Morton order, whose rate a value's
// own level does not tell. Rotations are left out: smallest-three coding takes each
// quaternion's three smallest components, which change with the one dropped.
//
// Measured (docs/results/2026-11-30-readme-notebook.md, "Rate-aware keyframe training"): on the
// default scene's keyframe at r1 the rate term costs more quality for its bytes than one bit less
// on positions does, so every rate point keeps lambda_k = 0.
#ifndef M4D_ENCODER_TRAIN_KEYFRAME_RATE_TERM_H_
#define M4D_ENCODER_TRAIN_KEYFRAME_RATE_TERM_H_

#include <cstddef>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/train/gaussian_model.h"

namespace m4d {

// Adds lambda_k * dRate/dvalue to the gradients of the rows from `first` on, the rate being
// the bits of every row's values at `quantization`'s bits, and returns that rate in bits.
// Rows before `first` are counted in the histograms but not moved (a dependent keyframe's
// kept set). lambda_k = 0 adds nothing.
double AddKeyframeRateGradients(const GaussianModel& model,
                                const GaussianQuantization& quantization, double lambda_k,
                                size_t first, GaussianModel* gradients);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_KEYFRAME_RATE_TERM_H_
