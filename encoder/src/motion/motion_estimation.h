// Motion estimation of one inter frame (paper sections 3.3 and 4.2): the motion grid of frame
// t (and, on the first inter frame of a GOP, the shared MLP) trained so that the static set
// plus the moved dynamic set of frame t-1 render the training views of frame t, under
//   L_s2 = L_color + lambda_2 L_rate,
// with simulated quantization (uniform noise of one quantization step on the grid values)
// and L_rate the size of the noisy grid under the learned entropy model, in units of 100
// kilobits. The paper does not give its normalisation; L_color being a mean over pixels, a rate in
// coded size keeps the balance independent of the image size. In kilobits the paper's lambda_2 set
// made inter frames far smaller than the paper's and let their quality fall frame after frame, each
// frame saving a kilobyte the next keyframe spends many times over; in units of 100 kilobits the
// inter frames lose far less per frame, on Panoptic basketball and on the default scene
// (docs/results/2026-11-30-readme-notebook.md, "Inter frames that hold quality";
// docs/results/2026-11-30-comment-measurements.md).
//
// The dynamic set of frame t-1 is what the decoder reconstructed (closed loop); its positions
// do not change while the grid is trained, so each Gaussian reads fixed voxels (MotionStencil)
// and only those voxels are trained; all other voxels stay zero.
#ifndef M4D_ENCODER_MOTION_MOTION_ESTIMATION_H_
#define M4D_ENCODER_MOTION_MOTION_ESTIMATION_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "encoder/src/metrics/photometric_loss.h"
#include "encoder/src/motion/logistic_entropy_model.h"
#include "encoder/src/motion/motion_field.h"
#include "encoder/src/motion/motion_stencil.h"
#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/train/encode_context.h"
#include "encoder/src/train/frozen_layer_views.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

struct MotionEstimationOptions {
  // 100 left the grid under-trained (each of Panoptic's views seen a few times:
  // docs/results/2026-11-30-readme-notebook.md, "Inter frames that hold quality"). With 130 the
  // frames late in a GOP drifted below 400's; 200 with the paper's lambda_2 keeps every frame near
  // 400's (within the target) at the same bytes, in half the time ("Faster inter frames"
  // there).
  int iterations = 200;
  int views_per_step = 1;           // training views rendered for each step (their mean loss)
  float grid_learning_rate = 0.5f;  // in quantization steps per iteration (Adam)
  float mlp_learning_rate = 1e-3f;
  float entropy_learning_rate = 1e-2f;
  double rate_weight = 1e-4;          // lambda_2
  bool simulate_quantization = true;  // off: plain float grid during training
  bool rate_term = true;              // off: L_s2 = L_color (ablation)
  bool train_mlp = false;             // the first inter frame of a GOP
  bool warm_start = true;             // start from the previous frame's grid
  // The dynamic set's colour change (APPEARANCE, appearance_estimation.h), trained with the
  // motion: its quantization step in SH DC units (0: none) and its learning rate in steps
  // per iteration (Adam), decaying like the grid's.
  float appearance_step = 1.0f / 64.0f;
  float appearance_learning_rate = 0.5f;
  // Every k-th training view (k-1, 2k-1, ...) trains no colour change, so that the appearance
  // decision can judge it on views it did not fit (AppearanceCheckViews; 0: every view trains).
  int appearance_check_every = 4;
  double ssim_weight = kDefaultSsimWeight;
  int sh_degree = 3;
  EncodeContext context;
};

struct MotionEstimationResult {
  // Integer grid values (rounded), the MLP, the stencil they were trained for.
  MotionParameters parameters;
  MotionStencil stencil;
  GridBox box;
  // Per Gaussian of the dynamic set: the 7 motion outputs with the rounded grid (zero for
  // Gaussians outside the box), for the splitting of compensation.
  std::vector<float> motion;
  double rate_bits = 0;  // entropy-model estimate of the rounded grid, in bits
  // With an appearance step: the colour change, 3 integers per Gaussian of the dynamic set
  // (in steps), and their estimated bits; empty without.
  std::vector<int32_t> appearance;
  double appearance_bits = 0;
  double color_loss = 0;  // mean L_color over the last pass through the views
};

class MotionEstimator {
 public:
  MotionEstimator(const GridConfig& config, const MlpConfig& mlp_config, const float* steps);

  // A new GOP: a fresh MLP (seeded) and no previous grid to start from.
  void StartGop(uint64_t seed);

  // Trains the motion of one frame: static_set and dynamic_set are frame t-1's decoded sets,
  // views frame t's training views. static_views, when given, is static_set's for these
  // views' cameras, kept for the GOP (null: made for this call).
  Status Estimate(const TrainingViews& views, const GaussianSet& static_set,
                  const GaussianSet& dynamic_set, const GridBox& box,
                  const MotionEstimationOptions& options, MotionEstimationResult* result,
                  FrozenLayerViews* static_views = nullptr);

  const MlpWeights& mlp() const { return mlp_; }
  const LogisticEntropyModel& entropy_model() const { return entropy_; }
  const GridConfig& config() const { return config_; }
  const float* steps() const { return steps_; }

 private:
  // Bits of the grid under the entropy model; adds the gradients of weight * bits. Each
  // (level, channel) has its own distribution and gradient entries, so they are spread over
  // `pool` (null: the calling thread) and their bits summed in order: the same result.
  double RateAndGradient(const MotionParameters& noisy, double weight, MotionParameters* grad,
                         std::vector<float>* entropy_grad, ThreadPool* pool) const;

  GridConfig config_;
  MlpConfig mlp_config_;
  float steps_[kMaxGridLevels] = {};
  MlpWeights mlp_;
  LogisticEntropyModel entropy_;
  // The previous frame's rounded grid, by dense voxel index, for warm starts.
  std::vector<uint32_t> previous_active_[kMaxGridLevels];
  std::vector<float> previous_values_[kMaxGridLevels];
};

// A grid box around the dynamic set: per axis the [lower, upper] quantiles of the positions,
// widened by `margin` of the extent on each side (outliers get no motion, as the decoder
// leaves Gaussians outside the box unchanged).
GridBox DynamicGridBox(const GaussianSet& dynamic_set, float lower = 0.005f, float upper = 0.995f,
                       float margin = 0.1f);

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_MOTION_ESTIMATION_H_
