#include "encoder/src/train/keyframe_trainer.h"

#include <algorithm>

#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "encoder/src/metrics/psnr.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/train/adaptive_density_control.h"
#include "encoder/src/train/gaussian_optimizer.h"
#include "encoder/src/train/importance_pruning.h"
#include "encoder/src/train/keyframe_rate_term.h"
#include "encoder/src/train/scene_extent.h"

namespace m4d {
namespace {

constexpr double kEmaWeight = 0.4;           // of the newest value, as the reference's progress bar
constexpr int kSmoothingRefitInterval = 10;  // iterations between refits of the 3D filter

// Zeroes every parameter of the first `rows` Gaussians (the frozen ones' gradients, so that
// Adam, whose moments then stay zero, never moves them).
void ZeroLeadingRows(size_t rows, GaussianModel* model) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    std::vector<float>& v = model->values(param);
    std::fill(
        v.begin(),
        v.begin() + static_cast<std::ptrdiff_t>(rows * static_cast<size_t>(model->width(param))),
        0.0f);
  }
}

// Copies every parameter of the first `rows` Gaussians of `from` into `to` (same SH degree).
void CopyLeadingRows(const GaussianModel& from, size_t rows, GaussianModel* to) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    const std::vector<float>& v = from.values(param);
    std::copy(
        v.begin(),
        v.begin() + static_cast<std::ptrdiff_t>(rows * static_cast<size_t>(from.width(param))),
        to->values(param).begin());
  }
}
constexpr float kShortGaussiansPerPixel = 0.25f;       // keyframe_trainer.h, Short()
constexpr float kShortMinImportancePixels = 0.05f;     // keyframe_trainer.h, min_importance_pixels
constexpr size_t kShortBackgroundShellPoints = 20000;  // keyframe_trainer.h, Short()

Status OptionError(const std::string& what) {
  return Status(M4D_ERR_INVALID_ARG, "keyframe training options: " + what);
}

}  // namespace

KeyframeTrainingOptions KeyframeTrainingOptions::Reference() { return KeyframeTrainingOptions(); }

KeyframeTrainingOptions KeyframeTrainingOptions::Short(int iterations) {
  KeyframeTrainingOptions o;
  iterations = std::max(iterations, 1);
  // The 7000-iteration schedule's proportions at any length: densification over the first
  // half (from 1/14 of the run), one opacity reset at 3/7, full SH degree at a tenth.
  o.iterations = iterations;
  o.learning_rates.position.max_steps = iterations;
  o.densify_from = std::max(1, iterations / 14);
  o.densify_until = iterations / 2;
  o.densify_interval = std::clamp(iterations / 70, 1, 100);
  o.opacity_reset_interval = std::max(1, iterations * 3 / 7);
  o.sh_degree_interval = std::max(1, iterations / 30);
  // Half the window between the reset and the end of densification, so that pruning still
  // follows the reset (a 100-iteration wait outlasted the window below 1400 iterations).
  o.reset_recovery = std::clamp((o.densify_until - o.opacity_reset_interval) / 2, 1, 100);
  o.densification.max_gaussians = 1000000;
  o.max_gaussians_per_pixel = kShortGaussiansPerPixel;
  o.quantization_aware_iterations = iterations / 4;
  o.min_importance_pixels = kShortMinImportancePixels;
  o.densification.max_prune_fraction = 0.5f;
  // The reference's screen-size test never fires (densification.h); ours, at 20 px, pruned
  // the floor near the cameras of a 640x360 capture.
  o.densification.max_screen_radius = 0.0f;
  o.camera_colour_learning_rate = 2e-3f;
  o.background_shell_points = kShortBackgroundShellPoints;
  // Coarse-to-fine stays off (levels 0): at the same iterations it lost on the default scene
  // and gained within noise on Panoptic (docs/design/densification_strategies.md). Turned on, it
  // spans the first quarter of the run.
  o.coarse_to_fine.until = iterations / 4;
  return o;
}

size_t GaussianCap(const KeyframeTrainingOptions& options, const TrainingViews& views) {
  const size_t cap = options.densification.max_gaussians;
  if (!(options.max_gaussians_per_pixel > 0.0f)) return cap;
  double pixels = 0;
  for (const Camera& c : views.cameras) pixels += static_cast<double>(c.width) * c.height;
  const double per_pixel = std::max(1.0, std::floor(options.max_gaussians_per_pixel * pixels));
  return per_pixel < static_cast<double>(cap) ? static_cast<size_t>(per_pixel) : cap;
}

Status ValidateTrainingOptions(const KeyframeTrainingOptions& o) {
  if (o.iterations < 0) return OptionError("negative iteration count");
  if (o.reset_recovery < 0) return OptionError("negative reset recovery");
  if (o.densify_from < 0 || o.densify_until < 0 || o.densify_interval < 0 ||
      o.opacity_reset_interval < 0 || o.sh_degree_interval < 0) {
    return OptionError("negative interval");
  }
  if (o.start_sh_degree < 0 || o.start_sh_degree > 3) return OptionError("start SH degree");
  if (o.sh_degree < 0 || o.sh_degree > 3) return OptionError("SH degree");
  if (!(o.ssim_weight >= 0.0 && o.ssim_weight <= 1.0)) return OptionError("SSIM weight");
  if (!(o.smoothing_filter_variance >= 0.0f && o.smoothing_filter_variance <= 100.0f)) {
    return Status(M4D_ERR_INVALID_ARG, "smoothing_filter_variance must be in [0, 100]");
  }
  if (!(o.camera_colour_learning_rate >= 0.0f && o.camera_colour_learning_rate <= 1.0f)) {
    return OptionError("camera colour learning rate");
  }
  if (!(o.sweep_share > 0.0f && o.sweep_share <= 1.0f)) return OptionError("sweep share");
  if (!(o.max_gaussians_per_pixel >= 0.0f) || !std::isfinite(o.max_gaussians_per_pixel)) {
    return OptionError("Gaussians per pixel");
  }
  if (o.quantization_aware_iterations < 0) return OptionError("negative quantization-aware count");
  if (!(o.rate_weight >= 0.0 && o.rate_weight <= 1e3)) return OptionError("rate weight");
  if (!(o.importance_prune_share >= 0.0f && o.importance_prune_share < 1.0f)) {
    return OptionError("importance prune share outside [0, 1)");
  }
  if (!(o.min_importance_pixels >= 0.0f) || !std::isfinite(o.min_importance_pixels)) {
    return OptionError("minimum importance");
  }
  if (!(o.opacity_reset_value > 0.0f && o.opacity_reset_value < 1.0f)) {
    return OptionError("opacity reset value");
  }
  if (!(o.scene_extent >= 0.0f) || !std::isfinite(o.scene_extent)) {
    return OptionError("scene extent");
  }
  if (o.context.threads < 0 || o.context.threads > kMaxRenderThreads)
    return OptionError("thread count");
  M4D_RETURN_IF_ERROR(ValidateCoarseToFine(o.coarse_to_fine));
  const DensificationSettings& d = o.densification;
  if (!(d.gradient_threshold >= 0.0f) || !(d.percent_dense >= 0.0f) ||
      !(d.min_opacity > 0.0f && d.min_opacity < 1.0f) || !(d.max_screen_radius >= 0.0f) ||
      !(d.max_world_scale > 0.0f) || !(d.split_scale_divisor > 0.0f) ||
      !(d.max_prune_fraction >= 0.0f && d.max_prune_fraction <= 1.0f) ||
      d.max_gaussians > kMaxRenderGaussians) {
    return OptionError("densification settings");
  }
  const McmcSettings& m = o.mcmc;
  if (!(m.growth >= 0.0f && m.growth <= 1.0f) || !(m.min_opacity > 0.0f && m.min_opacity < 1.0f) ||
      !(m.noise_learning_rate >= 0.0f) || !std::isfinite(m.noise_learning_rate) ||
      !(m.opacity_regularization >= 0.0f) || !std::isfinite(m.opacity_regularization) ||
      !(m.scale_regularization >= 0.0f) || !std::isfinite(m.scale_regularization)) {
    return OptionError("MCMC settings");
  }
  const GaussianLearningRates& r = o.learning_rates;
  for (float lr : {r.position.initial, r.position.final, r.sh_dc, r.sh_rest, r.opacity, r.scaling,
                   r.rotation}) {
    if (!(lr >= 0.0f) || !std::isfinite(lr)) return OptionError("learning rate");
  }
  if ((r.position.initial > 0.0f) != (r.position.final > 0.0f)) {
    return OptionError("position learning rates must be both zero or both positive");
  }
  return Status::Ok();
}

Status KeyframeTrainer::Init(const KeyframeTrainingOptions& options, TrainingViews views,
                             GaussianModel initial) {
  M4D_RETURN_IF_ERROR(ValidateTrainingOptions(options));
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  if (views.size() == 0) return Status(M4D_ERR_INVALID_ARG, "keyframe training: no views");
  if (initial.size() == 0) return Status(M4D_ERR_INVALID_ARG, "keyframe training: no Gaussians");
  if (options.frozen_gaussians > initial.size()) {
    return Status(M4D_ERR_INVALID_ARG, "keyframe training: more frozen Gaussians than given");
  }
  if (initial.size() > kMaxRenderGaussians) {
    return LimitError("keyframe training: too many Gaussians");
  }
  options_ = options;
  options_.densification.max_gaussians = GaussianCap(options, views);
  options_.densification.frozen = options.frozen_gaussians;
  scene_extent_ =
      options.scene_extent > 0.0f ? options.scene_extent : CameraSceneBounds(views.cameras).extent;
  if (!(scene_extent_ > 0.0f)) {
    return Status(M4D_ERR_INVALID_ARG,
                  "keyframe training: zero scene extent (set it when the cameras share a centre)");
  }
  M4D_RETURN_IF_ERROR(pyramid_.Build(views, options.coarse_to_fine));
  views_ = std::move(views);
  model_ = std::move(initial);
  gradients_ = GaussianModel();
  gradients_.sh_degree = model_.sh_degree;
  optimizer_ = MakeGaussianOptimizer(model_, options.learning_rates, scene_extent_);
  strategy_ =
      MakeDensificationStrategy(options_, scene_extent_, options_.densification.max_gaussians);
  strategy_->Reset(model_.size());
  iteration_ = 0;
  active_sh_degree_ = std::min(options.start_sh_degree, model_.sh_degree);
  rng_.emplace(options.context.seed);
  view_order_.clear();
  view_cursor_ = 0;
  pool_ = std::make_shared<ThreadPool>(options.context.threads);
  loss_ = PhotometricLoss(options.ssim_weight);
  camera_colour_.Init(views_.size(), options.camera_colour_learning_rate);
  filter_ = SmoothingFilter3d();
  filter_baked_ = false;
  progress_ = TrainingProgress();
  progress_.iterations = options.iterations;
  progress_.gaussians = model_.size();
  importance_pruned_ = 0;
  tenths_.clear();
  largest_removal_ = 0;
  return Status::Ok();
}

int KeyframeTrainer::NextView() {
  if (view_cursor_ == view_order_.size()) {
    view_order_.resize(static_cast<size_t>(views_.size()));
    for (size_t v = 0; v < view_order_.size(); ++v) view_order_[v] = static_cast<int>(v);
    rng_->Shuffle(&view_order_);
    view_cursor_ = 0;
  }
  return view_order_[view_cursor_++];
}

RenderSettings KeyframeTrainer::Settings() const {
  RenderSettings settings;
  settings.sh_degree = active_sh_degree_;
  options_.context.ApplyTo(&settings);
  return settings;
}

Status KeyframeTrainer::ForwardBackward(int view) {
  const TrainingViews* coarse = pyramid_.At(iteration_);
  const TrainingViews& views = coarse != nullptr ? *coarse : views_;
  const Camera& camera = views.cameras[static_cast<size_t>(view)];
  const Image& target = views.images[static_cast<size_t>(view)];
  if (QuantizationAware()) {
    GaussianSet set;
    M4D_RETURN_IF_ERROR(ModelToGaussianSet(model_, model_.sh_degree, &set));
    M4D_RETURN_IF_ERROR(QuantizeGaussianSet(options_.quantization, &set));
    M4D_RETURN_IF_ERROR(ModelFromGaussianSet(set, model_.sh_degree, &quantized_));
    CopyLeadingRows(model_, options_.frozen_gaussians, &quantized_);  // coded as they are
  }
  M4dGaussians layer = GaussianView(QuantizationAware() ? quantized_ : model_);
  if (Smoothing()) {
    filter_.Apply(model_);
    layer = filter_.View(model_);
  }
  M4D_RETURN_IF_ERROR(RenderForward(camera, &layer, 1, Settings(), nullptr, &context_));
  Reshape(camera.width, camera.height, 3, &rendered_);
  std::copy(context_.color.begin(), context_.color.end(), rendered_.pixels.begin());
  if (camera_colour_.enabled()) camera_colour_.Apply(view, &rendered_);
  M4D_RETURN_IF_ERROR(loss_.Evaluate(rendered_, target, &last_loss_, &loss_gradient_));
  if (camera_colour_.enabled()) camera_colour_.Backward(view, rendered_, &loss_gradient_);

  gradients_.Resize(model_.size());
  mean2d_.resize(2 * model_.size());
  const LayerGradients layer_gradients = GradientView(&gradients_);
  SplatGradients out;
  out.layers = &layer_gradients;
  out.layer_count = 1;
  out.mean2d = mean2d_.data();
  M4D_RETURN_IF_ERROR(
      RenderBackward(loss_gradient_.pixels.data(), nullptr, &context_, out, &backward_workspace_));
  if (Smoothing()) filter_.Backward(model_, &gradients_);

  double mse = 0;
  M4D_RETURN_IF_ERROR(MeanSquaredError(rendered_, target, &mse));
  const double psnr = mse > 0 ? -10.0 * std::log10(mse) : 100.0;
  const bool first = iteration_ == 1;
  progress_.loss =
      first ? last_loss_.loss : kEmaWeight * last_loss_.loss + (1 - kEmaWeight) * progress_.loss;
  progress_.psnr = first ? psnr : kEmaWeight * psnr + (1 - kEmaWeight) * progress_.psnr;
  return Status::Ok();
}

bool KeyframeTrainer::QuantizationAware() const {
  return iteration_ > options_.iterations - options_.quantization_aware_iterations;
}

Status KeyframeTrainer::PruneUnimportant() {
  std::vector<double> weights;
  M4D_RETURN_IF_ERROR(BlendingWeights(Smoothing() ? FilteredModel() : model_, views_, Settings(),
                                      &context_, &backward_workspace_, &weights));
  std::vector<uint8_t> keep =
      KeepImportant(weights, options_.importance_prune_share, options_.min_importance_pixels,
                    options_.densification.max_prune_fraction);
  std::fill(keep.begin(), keep.begin() + static_cast<std::ptrdiff_t>(options_.frozen_gaussians), 1);
  // What no training view sees is removed without bound (it is harmless to them all) and
  // is not counted as lost.
  size_t seen_removed = 0;
  for (size_t i = 0; i < keep.size(); ++i) seen_removed += !keep[i] && weights[i] > 0.0;
  const size_t before = model_.size();
  KeepGaussians(keep, &model_, &optimizer_, nullptr);
  importance_pruned_ += before - model_.size();
  largest_removal_ =
      std::max(largest_removal_, static_cast<double>(seen_removed) /
                                     static_cast<double>(std::max<size_t>(before, 1)));
  return Status::Ok();
}

Status KeyframeTrainer::Step() {
  if (!rng_) return Status(M4D_ERR_INVALID_ARG, "keyframe training: not initialised");
  const int it = ++iteration_;
  optimizer_.SetLearningRate(kGroupPositions,
                             options_.learning_rates.position.At(it) * scene_extent_);
  if (options_.sh_degree_interval > 0 && it % options_.sh_degree_interval == 0 &&
      active_sh_degree_ < model_.sh_degree) {
    ++active_sh_degree_;
  }
  RefitSmoothingFilter(it);
  M4D_RETURN_IF_ERROR(ForwardBackward(NextView()));

  const Camera& camera = context_.camera;
  StrategyStep step;
  step.iteration = it;
  step.position_learning_rate = optimizer_.learning_rate(kGroupPositions);
  step.splats = &context_.splats;
  step.mean2d = mean2d_.data();
  step.width = camera.width;
  step.height = camera.height;
  const StrategyState state{&model_, &optimizer_, &*rng_};
  StrategyOutcome outcome;
  M4D_RETURN_IF_ERROR(strategy_->AfterBackward(step, state, &outcome));
  if (outcome.before > 0) {
    largest_removal_ = std::max(largest_removal_, static_cast<double>(outcome.removed) /
                                                      static_cast<double>(outcome.before));
  }
  bool densified = outcome.rows_changed;
  const bool prunes =
      options_.importance_prune_share > 0.0f || options_.min_importance_pixels > 0.0f;
  if (prunes && it == options_.densify_until) {
    M4D_RETURN_IF_ERROR(PruneUnimportant());
    densified = true;  // this iteration's gradients belong to the Gaussians before pruning
  }
  if (!densified) {
    if (QuantizationAware()) {
      AddKeyframeRateGradients(model_, options_.quantization, options_.rate_weight,
                               options_.frozen_gaussians, &gradients_);
    }
    strategy_->Regularize(model_, &gradients_);
    ZeroLeadingRows(options_.frozen_gaussians, &gradients_);
    StepGaussianOptimizer(gradients_, outcome.skip_step, &optimizer_, &model_, pool_.get());
  }
  strategy_->AfterStep(step, state);
  BakeSmoothingFilter(it);
  progress_.iteration = it;
  progress_.gaussians = model_.size();
  RecordTenth();
  return Status::Ok();
}

// Every few iterations and whenever the rows changed count: a Gaussian's filter follows its
// centre, and densification or relocation moves centres.
void KeyframeTrainer::RefitSmoothingFilter(int iteration) {
  if (!Smoothing()) return;
  if (filter_.size() == model_.size() && iteration % kSmoothingRefitInterval != 0) return;
  filter_.Fit(model_, views_.cameras, options_.smoothing_filter_variance,
              options_.frozen_gaussians);
}

// Before the quantization-aware iterations (which render the model as coded), else after the
// last: what leaves the trainer is plain 3D Gaussians.
void KeyframeTrainer::BakeSmoothingFilter(int iteration) {
  if (!Smoothing()) return;
  if (iteration < options_.iterations - options_.quantization_aware_iterations) return;
  filter_.Fit(model_, views_.cameras, options_.smoothing_filter_variance,
              options_.frozen_gaussians);
  filter_.Apply(model_);
  filter_.Bake(&model_);
  filter_baked_ = true;
}

void KeyframeTrainer::RecordTenth() {
  const int total = options_.iterations;
  const int tenth = static_cast<int>(tenths_.size()) + 1;
  if (total <= 0 || tenth > 10 || iteration_ < (static_cast<int64_t>(total) * tenth + 9) / 10) {
    return;
  }
  tenths_.push_back({iteration_, model_.size(), progress_.loss, progress_.psnr});
}

Status KeyframeTrainer::Train(const ProgressCallback& progress, int progress_every) {
  return TrainUntil(options_.iterations, progress, progress_every);
}

Status KeyframeTrainer::TrainUntil(int last, const ProgressCallback& progress, int progress_every) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_report = Clock::now();
  int last_iteration = iteration_;
  last = std::min(last, options_.iterations);
  while (iteration_ < last) {
    M4D_RETURN_IF_ERROR(Step());
    const bool report =
        progress_every > 0 && (iteration_ % progress_every == 0 || iteration_ == last);
    if (progress && report) {
      const Clock::time_point now = Clock::now();
      const double seconds = std::chrono::duration<double>(now - last_report).count();
      progress_.iterations_per_second = seconds > 0 ? (iteration_ - last_iteration) / seconds : 0;
      last_report = now;
      last_iteration = iteration_;
      progress(progress_);
    }
  }
  return Status::Ok();
}

Status KeyframeTrainer::Evaluate(const TrainingViews& views, EvaluationResult* result) {
  if (!rng_) return Status(M4D_ERR_INVALID_ARG, "keyframe training: not initialised");
  return EvaluateViews(Smoothing() ? FilteredModel() : model_, views, Settings(), &context_,
                       result);
}

GaussianModel KeyframeTrainer::FilteredModel() const {
  SmoothingFilter3d filter;
  filter.Fit(model_, views_.cameras, options_.smoothing_filter_variance, options_.frozen_gaussians);
  filter.Apply(model_);
  GaussianModel filtered = model_;
  filter.Bake(&filtered);
  return filtered;
}

StrategyHolder MakeDensificationStrategy(const KeyframeTrainingOptions& options, float scene_extent,
                                         size_t cap) {
  if (options.strategy == DensificationStrategyKind::kMcmc) {
    McmcSettings mcmc = options.mcmc;
    mcmc.max_gaussians = cap;
    mcmc.refine_from = options.densify_from;
    mcmc.refine_until = options.densify_until;
    mcmc.refine_interval = options.densify_interval;
    mcmc.frozen = options.frozen_gaussians;
    return StrategyHolder(std::make_unique<McmcDensification>(mcmc));
  }
  AdaptiveDensitySchedule adc;
  adc.settings = options.densification;
  adc.settings.max_gaussians = cap;
  adc.settings.frozen = options.frozen_gaussians;
  adc.densify_from = options.densify_from;
  adc.densify_until = options.densify_until;
  adc.densify_interval = options.densify_interval;
  adc.opacity_reset_interval = options.opacity_reset_interval;
  adc.opacity_reset_value = options.opacity_reset_value;
  adc.reset_recovery = options.reset_recovery;
  return StrategyHolder(std::make_unique<AdaptiveDensityControl>(adc, scene_extent));
}

}  // namespace m4d
