// The optimizer of a GaussianModel: an AdamOptimizer with one parameter per model array
// (in GaussianParameter order) and the reference 3DGS's groups, so that stages can set
// rates or freeze groups by name (the lookahead stage trains positions and scales only).
#ifndef M4D_ENCODER_TRAIN_GAUSSIAN_OPTIMIZER_H_
#define M4D_ENCODER_TRAIN_GAUSSIAN_OPTIMIZER_H_

#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/learning_rate_schedule.h"
#include "sdk/src/common/thread_pool.h"

namespace m4d {

// Group indices of MakeGaussianOptimizer's optimizer.
enum GaussianGroup : int {
  kGroupPositions,  // "xyz"
  kGroupShDc,       // "f_dc": SH columns 0..2
  kGroupShRest,     // "f_rest": the higher bands (absent when the model has degree 0)
  kGroupOpacity,    // "opacity"
  kGroupScaling,    // "scaling"
  kGroupRotation,   // "rotation"
};

// An optimizer for `model` (its size and SH degree) with the rates of `rates`; the position
// rate is rates.position.At(0) * spatial_scale until the caller sets it.
AdamOptimizer MakeGaussianOptimizer(const GaussianModel& model, const GaussianLearningRates& rates,
                                    float spatial_scale);

// One Adam step of every parameter of model with the gradients in `gradients` (same size),
// skipping `skip` (kGaussianParameterCount: none).
void StepGaussianOptimizer(const GaussianModel& gradients, GaussianParameter skip,
                           AdamOptimizer* optimizer, GaussianModel* model, ThreadPool* pool);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_GAUSSIAN_OPTIMIZER_H_
