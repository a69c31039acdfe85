#include "encoder/src/run/train_run.h"

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
#include "encoder/src/run/keyframe_bits_choice.h"
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

namespace m4d {
namespace {

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

}  // namespace

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
  const std::vector<KeyframeBitsCandidate> offered =
      OfferedKeyframeBits(args.rate_point, !args.keyframe_bits.empty());
  KeyframeBitsChoice bits;
  M4D_RETURN_IF_ERROR(ChooseKeyframeBits(offered, args.prune.bits_max_loss_per_halving_db,
                                         choice.prune.branch, &bits));
  // Trained for the rate point's bits, coded at those chosen (as the encoder does).
  const GaussianQuantization coded = bits.chosen > 0
                                         ? offered[static_cast<size_t>(bits.chosen)].quantization
                                         : options.quantization;
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
    M4D_RETURN_IF_ERROR(PrintCodedQuality(model, args.sh_degree, coded, test, settings));
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

}  // namespace m4d
