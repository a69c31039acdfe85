// KeyframeTrainer: the 3DGS optimisation of one frame's Gaussians (Kerbl et al. 2023, as its
// reference implementation runs it): each iteration renders one training view (views in a
// seeded random order, reshuffled every pass), takes the loss (1 - lambda) L1 + lambda
// (1 - SSIM) and its gradient through the rasterizer, and steps Adam, with the position
// learning rate decaying, the active SH degree rising, and a densification strategy
// (densification_strategy.h: the reference's adaptive density control, or MCMC) for the first
// part of the run.
//
// Order within iteration i (1-based), as the reference: learning rates for i; SH degree up
// when i is a multiple of sh_degree_interval; render, loss, backward; the strategy's
// AfterBackward (adaptive density control, while i < densify_until: gather statistics,
// densify when i > densify_from and i is a multiple of densify_interval, reset opacities
// when i is a multiple of opacity_reset_interval); then the Adam step, except after the
// model's rows changed (the reference's densified tensors lose that iteration's gradients)
// and for the opacities just reset; then the strategy's AfterStep.
//
// Same options and seed give the same model bit for bit, whatever the thread count.
//
// The loop's parts are separate so that later stages reuse them: a trainer can start from a
// previous model (retraining a keyframe), with densification off and optimizer groups frozen
// (the lookahead fine-tuning of positions and scales).
#ifndef M4D_ENCODER_TRAIN_KEYFRAME_TRAINER_H_
#define M4D_ENCODER_TRAIN_KEYFRAME_TRAINER_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/image/image.h"
#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/metrics/photometric_loss.h"
#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/train/adam_optimizer.h"
#include "encoder/src/train/camera_colour.h"
#include "encoder/src/train/coarse_to_fine.h"
#include "encoder/src/train/densification.h"
#include "encoder/src/train/densification_strategy.h"
#include "encoder/src/train/encode_context.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/learning_rate_schedule.h"
#include "encoder/src/train/mcmc_densification.h"
#include "encoder/src/train/progress_bar.h"
#include "encoder/src/train/smoothing_filter_3d.h"
#include "encoder/src/train/training_random.h"
#include "encoder/src/train/training_views.h"
#include "encoder/src/train/view_evaluation.h"
#include "sdk/src/common/status.h"
#include "sdk/src/common/thread_pool.h"

namespace m4d {

struct KeyframeTrainingOptions {
  int iterations = 30000;
  // The position rate decays over learning_rates.position.max_steps.
  GaussianLearningRates learning_rates;
  DensificationSettings densification;
  // Caps densification.max_gaussians at this many Gaussians per pixel of the training views
  // (0: no such cap), and with it the points drawn for a capture without any (a capture's own
  // points are kept: densification then only refills what pruning removes). What more
  // Gaussians than the views resolve add is fitted noise: see Short().
  float max_gaussians_per_pixel = 0.0f;
  // When densification ends (iteration densify_until), the least important Gaussians that
  // together hold this share of the views' blending weight are removed (importance_pruning.h;
  // 0: none); the rest of the run fine-tunes the others. What a capture affords differs
  // (prune_share_selection.h chooses it; the encoder's command line does by default).
  float importance_prune_share = 0.0f;
  // At the same iteration, Gaussians whose blending weight summed over every pixel of every
  // training view is below this many pixels are removed too (0: none): all they add to all
  // the views together is that many pixels' colour at most, yet each costs the keyframe as
  // many bytes as any other (Short(): 0.05, about a quarter of a sparse rig's keyframe). A
  // later keyframe grows only what its prediction does not explain (retraining_growth.h), so
  // its retraining does not refill the room they leave.
  float min_importance_pixels = 0.0f;
  // The last this-many iterations render the model as the keyframe coder at `quantization`
  // will reconstruct it, and apply the gradients to the unquantized values (straight-through):
  // the model learns values whose quantization renders well (0: none).
  int quantization_aware_iterations = 0;
  // While quantization-aware, the loss gains lambda_k times the bits of the attributes the
  // keyframe coder codes as values, per 100 kilobits (keyframe_rate_term.h; 0: none).
  double rate_weight = 0.0;
  // The first this many Gaussians of the initial model stay exactly as given (a dependent
  // keyframe's kept static set): no step, never split or pruned (their clones are free).
  size_t frozen_gaussians = 0;
  GaussianQuantization quantization;
  // How the set of Gaussians grows and shrinks (densification_strategy.h). MCMC refines over
  // the same window as adaptive density control (densify_from, densify_until,
  // densify_interval), grows to GaussianCap, and starts its Gaussians at opacity 0.5 (the
  // paper's); adaptive density control's settings are `densification` and the resets below.
  DensificationStrategyKind strategy = DensificationStrategyKind::kAdaptiveDensityControl;
  McmcSettings mcmc;          // its noise, regularization, growth and min_opacity
  int densify_from = 500;     // densify only after this iteration
  int densify_until = 15000;  // statistics, densification and resets before it (0: none)
  int densify_interval = 100;
  int opacity_reset_interval = 3000;  // 0: never; size pruning starts after the first
  float opacity_reset_value = 0.01f;
  // Densification and pruning wait this many iterations after an opacity reset, so that what the
  // views need regains its opacity first (the reference's 100-iteration interval gives it that; a
  // short schedule's interval of 28 pruned most of a model). Short() waits half the window left
  // before densification ends: waiting longer than the window skips the pruning after the reset,
  // and the default scene's 1000-iteration keyframe then kept the Gaussians the reset left
  // transparent, and its inter frames drifted faster on the held-out camera
  // (docs/results/2026-11-30-readme-notebook.md, "Training does not collapse").
  int reset_recovery = 100;
  int sh_degree_interval = 1000;  // active SH degree + 1 every this many iterations (0: never)
  int start_sh_degree = 0;        // active at the start (the model's degree when retraining)
  int sh_degree = 3;              // SH degree of a model TrainKeyframe initialises (0..3)
  double ssim_weight = kDefaultSsimWeight;
  // Variance of Mip-Splatting's 3D smoothing filter in squared pixels of the finest training
  // camera seeing each Gaussian (smoothing_filter_3d.h; 0: none; the paper's 0.2). The filter
  // is baked into the model before the quantization-aware iterations, or at the end.
  float smoothing_filter_variance = 0.0f;
  // Adam's rate for a colour gain and offset per training view (camera_colour.h; 0: none).
  // Short() learns them (keyframes and their retraining); the lookahead fine-tuning, its
  // colours frozen, does not.
  float camera_colour_learning_rate = 0.0f;
  // The first iterations fit downscaled views (coarse_to_fine.h; levels 0: none).
  CoarseToFineSchedule coarse_to_fine;
  EncodeContext context;
  float scene_extent = 0.0f;  // 0: CameraSceneBounds of the training cameras
  // Without points: this many Gaussians from photo_consistent_points.h, or at random in the
  // part of the cameras' box two views see (random_initialisation; random_start.h).
  size_t random_points = 100000;
  bool random_initialisation = false;
  // The photo-consistent sweep is asked for this share of the start's points. Fewer, sparser
  // points help some captures and cost others (start_size_selection.h chooses it per capture).
  float sweep_share = 1.0f;
  // Without points, this many points spread over the background shell (background_shell.h) join the
  // start, those no two views see dropped, at most a quarter of the start (0: none). Short()
  // spreads 20000: on Panoptic basketball the dome wall then stands where the held-out cameras see
  // it (docs/results/, 2026-11-29).
  size_t background_shell_points = 0;

  // The reference implementation's defaults (30000 iterations).
  static KeyframeTrainingOptions Reference();
  // A 7000-iteration schedule for a CPU: the reference's intervals where they fit
  // (densify from 500 every 100 iterations, opacity reset every 3000), densification until
  // half the run (3500, like the reference's 15000 of 30000), so one opacity reset and 500
  // iterations of size pruning; position decay over 7000 iterations; SH degree up every 233
  // iterations (1000 x 7000 / 30000, full degree at 10% of the run as in the reference);
  // at most 1 million Gaussians, and at most a quarter of a Gaussian per training pixel.
  // The quarter was measured (docs/results/2026-11-30-readme-notebook.md, "Densification is bounded
  // by the views' pixels"): on the realistic scene's three views the unbounded keyframe went far
  // past it; bounded, it has half the Gaussians and renders its held-out view better, while the
  // default scene's fifteen views, well under it, are left as they were. No importance pruning by
  // share: the share a capture affords is chosen per capture (prune_share_selection.h), not by the
  // schedule. The last quarter of the run is quantization-aware (at `quantization`, which the
  // encoder sets to its rate point's keyframe bits). The same proportions at another length
  // (Short() is Short(7000)): densification from iterations / 14 to half the run every
  // iterations / 70 (at most 100), the opacity reset at 3/7 of the run, SH degree up every
  // iterations / 30.
  static KeyframeTrainingOptions Short(int iterations = 7000);
};

// The Gaussian count options allow for these views: densification.max_gaussians, lowered by
// max_gaussians_per_pixel times the views' pixels (at least 1).
size_t GaussianCap(const KeyframeTrainingOptions& options, const TrainingViews& views);

// Checks ranges and consistency; M4D_ERR_INVALID_ARG names the bad option.
Status ValidateTrainingOptions(const KeyframeTrainingOptions& options);

using ProgressCallback = std::function<void(const TrainingProgress&)>;

// The model's size and loss at one point of a run (KeyframeTrainer::tenths()).
struct TrainingTenth {
  int iteration = 0;
  size_t gaussians = 0;
  double loss = 0;  // the progress bar's moving averages
  double psnr = 0;
};

// The strategy the options ask for, for a trainer at this scene extent and Gaussian cap.
StrategyHolder MakeDensificationStrategy(const KeyframeTrainingOptions& options, float scene_extent,
                                         size_t cap);

class KeyframeTrainer {
 public:
  // Starts training `initial` on `views` (the model's SH degree is the largest trained).
  // Fails for bad options or views, an empty model, or a zero scene extent.
  Status Init(const KeyframeTrainingOptions& options, TrainingViews views, GaussianModel initial);

  // One iteration.
  Status Step();
  // Iterations until options.iterations, calling progress (if set) every progress_every
  // iterations and after the last.
  Status Train(const ProgressCallback& progress = nullptr, int progress_every = 10);
  // The same until iteration `last` (at most options().iterations).
  Status TrainUntil(int last, const ProgressCallback& progress = nullptr, int progress_every = 10);

  // Quality on `views` at the active SH degree and the training background.
  Status Evaluate(const TrainingViews& views, EvaluationResult* result);
  // The renders Evaluate makes: the active SH degree, the training background and threads.
  RenderSettings Settings() const;

  int iteration() const { return iteration_; }
  int active_sh_degree() const { return active_sh_degree_; }
  float scene_extent() const { return scene_extent_; }
  const KeyframeTrainingOptions& options() const { return options_; }
  const GaussianModel& model() const { return model_; }
  // The share a prune still to come removes (options().importance_prune_share): a copy of a
  // trainer stopped before densify_until continues as a branch with another share
  // (prune_share_selection.h). Copies share the thread pool.
  void SetImportancePruneShare(float share) { options_.importance_prune_share = share; }
  // The same for the rate weight of quantization-aware iterations still to come
  // (rate_weight_selection.h).
  void SetRateWeight(double weight) { options_.rate_weight = weight; }
  // Moves the model out; the trainer needs Init again afterwards.
  GaussianModel TakeModel() {
    rng_.reset();
    return std::move(model_);
  }
  // For stages that freeze groups or change rates (group indices: gaussian_optimizer.h).
  AdamOptimizer* optimizer() { return &optimizer_; }
  const TrainingProgress& progress() const { return progress_; }
  const PhotometricLossValue& last_loss() const { return last_loss_; }
  // Totals over the run.
  const StrategyCounts& densify_totals() const { return strategy_->counts(); }
  size_t importance_pruned() const { return importance_pruned_; }
  // The model's size and loss at every tenth of options().iterations reached so far.
  const std::vector<TrainingTenth>& tenths() const { return tenths_; }
  // The largest share of the model one densification, pruning or relocation event removed,
  // not counting Gaussians that no training view sees.
  double largest_removal() const { return largest_removal_; }

 private:
  int NextView();
  Status ForwardBackward(int view);
  Status PruneUnimportant();
  void RecordTenth();
  bool QuantizationAware() const;
  bool Smoothing() const { return options_.smoothing_filter_variance > 0.0f && !filter_baked_; }
  void RefitSmoothingFilter(int iteration);
  void BakeSmoothingFilter(int iteration);
  // The model as training renders it (the filter applied): what pruning and evaluation see.
  GaussianModel FilteredModel() const;

  KeyframeTrainingOptions options_;
  TrainingViews views_;
  ViewPyramid pyramid_;  // the coarse-to-fine levels of views_
  GaussianModel model_;
  GaussianModel gradients_;
  GaussianModel quantized_;  // what the forward pass renders while quantization-aware
  AdamOptimizer optimizer_;
  StrategyHolder strategy_;
  float scene_extent_ = 0;
  int iteration_ = 0;
  int active_sh_degree_ = 0;
  std::optional<TrainingRandom> rng_;
  std::vector<int> view_order_;
  size_t view_cursor_ = 0;

  // Per-iteration buffers, which a copy of the trainer does not need to share.
  template <typename T>
  struct Scratch : T {
    Scratch() = default;
    Scratch(const Scratch&) : T() {}
    Scratch& operator=(const Scratch&) { return *this; }
  };

  std::shared_ptr<ThreadPool> pool_;
  Scratch<RenderContext> context_;
  Scratch<BackwardWorkspace> backward_workspace_;
  PhotometricLoss loss_;
  Image rendered_;
  Image loss_gradient_;
  std::vector<float> mean2d_;
  CameraColour camera_colour_;
  SmoothingFilter3d filter_;
  bool filter_baked_ = false;

  PhotometricLossValue last_loss_;
  TrainingProgress progress_;
  size_t importance_pruned_ = 0;
  std::vector<TrainingTenth> tenths_;
  double largest_removal_ = 0;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_KEYFRAME_TRAINER_H_
