#include "tools/m4d/train_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/image_io/png_io.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "encoder/src/run/capture_arguments.h"
#include "encoder/src/run/prune_share_arguments.h"
#include "encoder/src/run/quality_curve.h"
#include "encoder/src/run/rate_weight_arguments.h"
#include "encoder/src/run/strategy_arguments.h"
#include "encoder/src/run/view_strip.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/progress_bar.h"
#include "encoder/src/train/view_evaluation.h"
#include "sdk/src/common/byte_writer.h"
#include "tools/existing_output.h"
#include "tools/m4d/command_status.h"
#include "tools/m4d/rate_point_name.h"
#include "tools/m4d/run_options.h"
#include "tools/number_checks.h"

namespace m4d {
namespace {

struct TrainArguments {
  CaptureArguments capture;
  int frame = 0;
  int iterations = 0;  // 0: the schedule's
  bool reference_schedule = false;
  int sh_degree = 3;
  int threads = 0;
  uint64_t seed = 1;
  bool random_init = false;
  std::string strategy;             // empty: the schedule's
  int max_gaussians = 0;            // 0: the schedule's
  int background_shell = -1;        // points (< 0: the schedule's)
  double gaussians_per_pixel = -1;  // < 0: the schedule's
  double smoothing_filter = -1;     // < 0: the schedule's
  int coarse_levels = -1;           // < 0: the schedule's
  double coarse_until = -1;         // share of the run (< 0: the schedule's)
  PruneShareArguments prune;
  double prune_below = -1;         // < 0: the schedule's
  int quantization_aware = -1;     // iterations (< 0: the schedule's)
  RateWeightArguments rate;        // lambda_k of the keyframe's rate term
  std::string rate_point = "r4";   // the keyframe bits the model is trained and coded for
  std::vector<int> keyframe_bits;  // 6 bit depths (empty: the rate point's)
  // Written only when asked for: a training run leaves nothing in the current folder unasked.
  std::string ply;     // the model (empty: none)
  std::string render;  // the held-out view beside its ground truth (empty: none)
  std::string curve;   // CSV of held-out quality over time (empty: none)
  bool force = false;  // replace those files when they exist
  std::vector<double> curve_minutes = {1, 2, 5, 10, 15, 20};
};

// The curve's clock starts with the command, before any automatic choice, and it needs the
// capture's test cameras.
Status StartQualityCurve(const TrainArguments& args, const Capture& capture,
                         std::unique_ptr<QualityCurve>* curve) {
  if (args.curve.empty()) return Status::Ok();
  if (capture.test_cameras.empty()) {
    return Status(M4D_ERR_INVALID_ARG, "--curve: the capture has no held-out camera");
  }
  M4D_RETURN_IF_ERROR(CheckOutputPath(args.curve));
  TrainingViews test;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, args.frame, capture.test_cameras, &test));
  RenderSettings settings;
  settings.threads = args.threads;
  settings.sh_degree = args.sh_degree;
  std::vector<double> marks = args.curve_minutes;
  std::sort(marks.begin(), marks.end());
  *curve = std::make_unique<QualityCurve>(std::move(marks), std::move(test), settings);
  return Status::Ok();
}

// The keyframe bits and rate term the model is trained for: the rate point's, or the arguments'.
Status TrainingRate(const TrainArguments& args, KeyframeTrainingOptions* options) {
  RatePointSettings point;
  M4D_RETURN_IF_ERROR(FindRatePoint(args.rate_point, &point));
  options->rate_weight = args.rate.weight >= 0 ? args.rate.weight : point.keyframe_rate_weight;
  GaussianQuantization* quantization = &options->quantization;
  *quantization = point.keyframe;
  if (args.keyframe_bits.size() == 6) {
    quantization->position_bits = args.keyframe_bits[0];
    quantization->log_scale_bits = args.keyframe_bits[1];
    quantization->rotation_bits = args.keyframe_bits[2];
    quantization->opacity_bits = args.keyframe_bits[3];
    quantization->sh_dc_bits = args.keyframe_bits[4];
    quantization->sh_rest_bits = args.keyframe_bits[5];
  }
  return Status::Ok();
}

// Held-out quality of the model as the keyframe coder reconstructs it, and its size.
Status PrintCodedQuality(const GaussianModel& model, int sh_degree,
                         const GaussianQuantization& quantization, const TrainingViews& test,
                         const RenderSettings& settings) {
  GaussianSet set, decoded;
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(model, sh_degree, &set));
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  M4D_RETURN_IF_ERROR(WriteGaussianSet(set, quantization, &writer));
  M4D_RETURN_IF_ERROR(ReconstructGaussianSet(set, quantization, &decoded));
  GaussianModel coded;
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(decoded, sh_degree, &coded));
  EvaluationResult quality;
  M4D_RETURN_IF_ERROR(EvaluateViews(coded, test, settings, nullptr, &quality));
  std::printf("%-28s %s: %.1f KB (%.2f bytes per Gaussian), held-out %.2f dB  SSIM %.4f\n",
              "coded as a keyframe", QuantizationName(quantization).c_str(), bytes.size() / 1000.0,
              static_cast<double>(bytes.size()) / std::max<size_t>(1, set.size()),
              quality.mean_psnr, quality.mean_ssim);
  return Status::Ok();
}

Status RunTrain(const TrainArguments& args) {
  Capture capture;
  M4D_RETURN_IF_ERROR(OpenCapture(args.capture, &capture));
  if (args.frame >= capture.frame_count) {
    return Status(M4D_ERR_INVALID_ARG, "frame " + std::to_string(args.frame) + " but only " +
                                           std::to_string(capture.frame_count) + " frames");
  }
  M4D_RETURN_IF_ERROR(CheckViewsBeforeTraining(capture, args.frame, 1));
  std::unique_ptr<QualityCurve> curve;
  M4D_RETURN_IF_ERROR(StartQualityCurve(args, capture, &curve));
  KeyframeTrainingOptions options = KeyframeTrainingOptions::Short();
  if (args.reference_schedule) options = KeyframeTrainingOptions::Reference();
  if (args.iterations > 0 && !args.reference_schedule) {
    options = KeyframeTrainingOptions::Short(args.iterations);
  }
  options.sh_degree = args.sh_degree;
  options.random_initialisation = args.random_init;
  ApplyStrategy(args.strategy, &options);
  if (args.max_gaussians > 0) options.densification.max_gaussians = args.max_gaussians;
  if (args.background_shell >= 0) {
    options.background_shell_points = static_cast<size_t>(args.background_shell);
  }
  if (args.gaussians_per_pixel >= 0) {
    options.max_gaussians_per_pixel = static_cast<float>(args.gaussians_per_pixel);
  }
  if (args.smoothing_filter >= 0) {
    options.smoothing_filter_variance = static_cast<float>(args.smoothing_filter);
  }
  if (args.coarse_levels >= 0) options.coarse_to_fine.levels = args.coarse_levels;
  if (args.coarse_until >= 0) {
    options.coarse_to_fine.until = static_cast<int>(args.coarse_until * options.iterations);
  }
  if (args.prune_below >= 0) options.min_importance_pixels = static_cast<float>(args.prune_below);
  if (args.quantization_aware >= 0) options.quantization_aware_iterations = args.quantization_aware;
  M4D_RETURN_IF_ERROR(TrainingRate(args, &options));
  options.context.threads = args.threads;
  options.context.seed = args.seed;
  KeyframeShareChoice choice;
  M4D_RETURN_IF_ERROR(ResolveKeyframeShares(capture, args.frame, args.prune, &options, &choice));
  RateWeightArguments rate = args.rate;
  rate.max_loss_per_halving_db = args.prune.max_loss_per_halving_db;
  RateWeightChoice rate_choice;
  M4D_RETURN_IF_ERROR(ResolveRateWeight(capture, args.frame, options, rate, options.rate_weight,
                                        &options.rate_weight, &rate_choice));
  const auto start = std::chrono::steady_clock::now();
  ProgressBar bar;
  GaussianModel model;
  KeyframeTrainingReport report;
  TrainerObserver observe = nullptr;
  if (curve) {
    observe = [&](KeyframeTrainer* trainer) { return curve->Observe(trainer); };
  }
  M4D_RETURN_IF_ERROR(TrainKeyframe(
      capture, args.frame, options, [&](const TrainingProgress& p) { bar.Update(p); }, &model,
      &report, observe));
  bar.Finish();
  if (curve) M4D_RETURN_IF_ERROR(curve->Finish(model, options.iterations));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  RenderSettings settings;
  settings.threads = args.threads;
  settings.sh_degree = args.sh_degree;
  TrainingViews train, test;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, args.frame, capture.TrainCameras(), &train));
  EvaluationResult train_quality, test_quality;
  M4D_RETURN_IF_ERROR(EvaluateViews(model, train, settings, nullptr, &train_quality));
  std::printf("\n%-28s %s\n", "keyframe training", capture.layout.c_str());
  std::printf("%-28s %d (%d views of %dx%d)\n", "frame", args.frame, train.size(),
              train.cameras[0].width, train.cameras[0].height);
  std::printf("%-28s %d (%s)\n", "iterations", options.iterations, StrategyName(options.strategy));
  PrintTrainingReport(report);
  std::printf("%-28s %zu (cap %zu)\n", "Gaussians", model.size(), GaussianCap(options, train));
  std::printf("%-28s %.1f s (%.1f ms per iteration)\n", "wall time", seconds,
              1000.0 * seconds / options.iterations);
  std::printf("%-28s %.2f dB  SSIM %.4f\n", "training views", train_quality.mean_psnr,
              train_quality.mean_ssim);
  if (!capture.test_cameras.empty()) {
    M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, args.frame, capture.test_cameras, &test));
    M4D_RETURN_IF_ERROR(EvaluateViews(model, test, settings, nullptr, &test_quality));
    std::printf("%-28s %.2f dB  SSIM %.4f\n", "held-out camera", test_quality.mean_psnr,
                test_quality.mean_ssim);
    std::printf("%-28s %.2f dB (a gain and offset per camera and channel fitted to its image)\n",
                "held-out, colour fitted", test_quality.mean_colour_fitted_psnr);
    M4D_RETURN_IF_ERROR(
        PrintCodedQuality(model, args.sh_degree, options.quantization, test, settings));
    if (!args.render.empty()) {
      Image rendered;
      RenderContext context;
      M4D_RETURN_IF_ERROR(RenderView(model, test.cameras[0], settings, &context, &rendered));
      M4D_RETURN_IF_ERROR(WriteViewStrip(args.render, {&test.images[0], &rendered}));
      std::printf("%-28s %s (ground truth | render)\n", "held-out view", args.render.c_str());
    }
  }
  if (curve) {
    curve->Print();
    M4D_RETURN_IF_ERROR(curve->WriteCsv(args.curve));
    std::printf("%-28s %s\n", "quality over time (CSV)", args.curve.c_str());
  }
  if (!args.ply.empty()) {
    GaussianSet set;
    M4D_RETURN_IF_ERROR(ModelToGaussianSet(model, model.sh_degree, &set));
    M4D_RETURN_IF_ERROR(WriteGaussianPly(args.ply, set));
    std::printf("%-28s %s\n", "model (3DGS PLY)", args.ply.c_str());
  }
  return Status::Ok();
}

}  // namespace

void AddTrainCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<TrainArguments>();
  CLI::App* cmd = app->add_subcommand(
      "train", "train one frame's 3D Gaussians (the keyframe stage) and report its quality");
  AddCaptureArguments(cmd, &args->capture);
  cmd->add_option("--frame", args->frame, "frame to train")->check(m4d::AtLeast(0));
  cmd->add_option("--gaussians-per-pixel", args->gaussians_per_pixel,
                  "at most this many Gaussians per pixel of the training views (0: no such "
                  "cap; default 0.25, none with --reference-schedule)")
      ->check(m4d::Within(0.0, 64.0));
  cmd->add_option("--smoothing-filter", args->smoothing_filter,
                  "variance of Mip-Splatting's 3D smoothing filter in squared pixels of the "
                  "finest training camera (0: none; Mip-Splatting's 0.2), baked into the model")
      ->check(m4d::Within(0.0, 100.0));
  AddPruneShareOptions(cmd, "keyframe training", &args->prune);
  cmd->add_option("--prune-below", args->prune_below,
                  "when densification ends, remove the Gaussians whose blending weight summed "
                  "over the views is below this many pixels (default 0.05, none with "
                  "--reference-schedule; 0: none)")
      ->check(m4d::Within(0.0, 1e6));
  cmd->add_option("--quantization-aware", args->quantization_aware,
                  "the last N iterations render the model as coded at the rate point (default: "
                  "a quarter of the run; 0: none)")
      ->check(m4d::AtLeast(0));
  AddRateWeightOption(cmd, &args->rate);
  cmd->add_option("--rate-point", args->rate_point,
                  "the rate point whose keyframe bits the model is trained for (quantization-"
                  "aware) and coded at in the report")
      ->check(RatePointName())
      ->capture_default_str();
  cmd->add_option("--keyframe-bits", args->keyframe_bits,
                  "those bits instead: position,scale,rotation,opacity,color,sh")
      ->expected(6)
      ->delimiter(',')
      ->check(m4d::Within(1, 24));
  cmd->add_flag("--random-init", args->random_init,
                "without initial points, start at random in the part of the cameras' box two "
                "views see (coloured from them) instead of from photo-consistent points");
  AddStrategyOption(cmd, &args->strategy);
  cmd->add_option("--max-gaussians", args->max_gaussians,
                  "at most this many Gaussians (MCMC: exactly this many, if the pixel cap allows; "
                  "default: the schedule's)")
      ->check(m4d::Within(1, 16777216));
  cmd->add_option("--background-shell", args->background_shell,
                  "without initial points, this many points over the sphere of the cameras join "
                  "the start (those no two views see dropped; 0: none)")
      ->check(m4d::Within(0, 1000000));
  cmd->add_option("--coarse-levels", args->coarse_levels,
                  "the first iterations fit views downscaled by 2^N, then by half as much, ... "
                  "(default 0: full size throughout)")
      ->check(m4d::Within(0, kMaxCoarseLevels));
  cmd->add_option("--coarse-until", args->coarse_until,
                  "with --coarse-levels, the share of the run before views are full size (default "
                  "0.25)")
      ->check(m4d::Within(0.0, 1.0));
  cmd->add_option("--iterations", args->iterations,
                  "iterations of the short schedule, its phases scaled (default 7000)")
      ->check(m4d::AtLeast(0));
  cmd->add_flag("--reference-schedule", args->reference_schedule,
                "the reference 3DGS schedule (30000 iterations) instead of the short one");
  cmd->add_option("--sh-degree", args->sh_degree, "SH degree")
      ->check(m4d::Within(0, 3))
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "threads (0: all cores)")->check(m4d::AtLeast(0));
  cmd->add_option("--seed", args->seed, "random seed")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--ply", args->ply, "write the model here (3DGS PLY)");
  cmd->add_option("--render", args->render,
                  "write the held-out view beside its ground truth here (PNG)");
  cmd->add_option("--curve", args->curve,
                  "write the held-out cameras' PSNR as the command's minutes pass (CSV: "
                  "minutes, iteration, Gaussians, PSNR; the clock stops while it evaluates)");
  cmd->add_option("--curve-minutes", args->curve_minutes, "the minutes --curve evaluates at")
      ->delimiter(',')
      ->check(m4d::Within(0.0, 1e6))
      ->capture_default_str();
  cmd->add_flag("-f,--force", args->force, "replace an existing --ply, --render or --curve file");
  cmd->callback([args, exit_code]() {
    // Outputs are checked before the minutes of training, from the command line: exit 2.
    for (const std::string* path : {&args->ply, &args->render, &args->curve}) {
      const Status may_write = RefuseExistingOutput(*path, args->force || path->empty());
      if (!may_write.ok()) {
        ReportStatus("train", may_write);
        *exit_code = 2;
        return;
      }
    }
    *exit_code = ReportStatus("train", RunTrain(*args));
  });
}

}  // namespace m4d
