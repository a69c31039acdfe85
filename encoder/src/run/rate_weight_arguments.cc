#include "encoder/src/run/rate_weight_arguments.h"

#include <cstdio>
#include <string>

#include "encoder/src/train/progress_bar.h"

namespace m4d {
namespace {

void PrintTrial(const char* run, const RateWeightTrial& trial, const RateWeightChoice& choice,
                double bound, bool chosen) {
  std::printf("  %-18s %8.1f KB  %6.2f dB", run, trial.bytes / 1000.0, trial.psnr);
  if (&trial != &choice.without) {
    std::printf("  %+5.2f dB  %5.2f dB", trial.psnr - choice.without.psnr,
                AllowedLoss(choice.without, trial, bound));
  }
  std::printf("%s\n", chosen ? "  chosen" : "");
}

void PrintChoice(const RateWeightChoice& choice, double bound) {
  if (choice.validation_cameras.empty()) {
    std::printf(
        "keyframe rate weight         0 (no training view to hold out, or no "
        "quantization-aware iterations)\n");
    return;
  }
  std::string cameras;
  for (int c : choice.validation_cameras) cameras += " " + std::to_string(c);
  std::printf(
      "rate weight selection        cameras%s held out, at most %.2f dB lost per halving of the "
      "bytes\n",
      cameras.c_str(), bound);
  std::printf("  %-18s %11s  %9s  %8s  %8s\n", "run", "coded", "held out", "loss", "allowed");
  PrintTrial("without rate term", choice.without, choice, bound, choice.weight == 0.0);
  for (const RateWeightTrial& t : choice.trials) {
    char run[32];
    std::snprintf(run, sizeof(run), "weight %g", t.weight);
    PrintTrial(run, t, choice, bound, t.weight == choice.weight);
  }
  std::printf("keyframe rate weight         %g\n", choice.weight);
}

}  // namespace

Status ResolveRateWeight(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                         const RateWeightArguments& args, double fallback, double* weight,
                         RateWeightChoice* choice) {
  *choice = RateWeightChoice();
  if (!args.automatic) {
    *weight = args.weight >= 0 ? args.weight : fallback;
    return Status::Ok();
  }
  RateWeightSelectionOptions selection;
  selection.held_out.max_loss_per_halving_db = args.max_loss_per_halving_db;
  ProgressBar bar;
  M4D_RETURN_IF_ERROR(SelectRateWeight(
      capture, frame, options, selection,
      [&](const std::string& run, const TrainingProgress& p) {
        bar.Update(p, "rate weight test, " + run);
        if (p.iteration == p.iterations) bar.Finish();
      },
      choice));
  PrintChoice(*choice, args.max_loss_per_halving_db);
  *weight = choice->weight;
  return Status::Ok();
}

nlohmann::json RateWeightJson(const RateWeightArguments& args, const RateWeightChoice& choice) {
  if (!args.automatic) return nullptr;
  auto trial = [](const RateWeightTrial& t) {
    return nlohmann::json{{"weight", t.weight}, {"bytes", t.bytes}, {"psnr", t.psnr}};
  };
  nlohmann::json trials = nlohmann::json::array();
  for (const RateWeightTrial& t : choice.trials) trials.push_back(trial(t));
  return {{"max_loss_per_halving_db", args.max_loss_per_halving_db},
          {"validation_cameras", choice.validation_cameras},
          {"without", trial(choice.without)},
          {"trials", trials},
          {"weight", choice.weight}};
}

}  // namespace m4d
