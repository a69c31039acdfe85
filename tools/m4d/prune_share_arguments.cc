#include "prune_share_arguments.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "number_checks.h"
#include "train/progress_bar.h"

namespace m4d {
namespace {

void PrintTrial(const char* run, const PruneShareTrial& trial, const PruneShareTrial& unpruned,
                const PruneShareSelectionOptions& selection, bool chosen) {
  std::printf("  %-12s %10zu  %8.1f KB  %6.2f dB", run, trial.gaussians, trial.bytes / 1000.0,
              trial.psnr);
  if (&trial != &unpruned) {
    std::printf("  %+5.2f dB  %5.2f dB", trial.psnr - unpruned.psnr,
                AllowedLoss(unpruned, trial, selection));
  }
  std::printf("%s\n", chosen ? "  chosen" : "");
}

void PrintChoice(const PruneShareChoice& choice, const PruneShareSelectionOptions& selection) {
  if (choice.validation_cameras.empty()) {
    std::printf("prune share                  0 (too few training views to hold one out)\n");
    return;
  }
  std::string cameras;
  for (int c : choice.validation_cameras) cameras += " " + std::to_string(c);
  std::printf(
      "prune share selection        cameras%s held out, at most %.2f dB lost per halving of the "
      "bytes\n",
      cameras.c_str(), selection.max_loss_per_halving_db);
  std::printf("  %-12s %10s  %11s  %9s  %8s  %8s\n", "run", "Gaussians", "coded", "held out",
              "loss", "allowed");
  PrintTrial("unpruned", choice.unpruned, choice.unpruned, selection, choice.share == 0.0f);
  for (const PruneShareTrial& t : choice.trials) {
    char run[32];
    std::snprintf(run, sizeof(run), "share %g", static_cast<double>(t.share));
    PrintTrial(run, t, choice.unpruned, selection, t.share == choice.share);
  }
  std::printf("prune share                  %g\n", static_cast<double>(choice.share));
}

// A share as written on the command line (0.1, not the float's 0.100000001).
double ShareValue(float share) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", static_cast<double>(share));
  return std::strtod(text, nullptr);
}

}  // namespace

void AddPruneShareOptions(CLI::App* command, const char* what, PruneShareArguments* args) {
  command
      ->add_option_function<std::string>(
          "--prune-share",
          [args](const std::string& value) {
            args->share = value == "auto" ? -1.0 : std::stod(value);
          },
          std::string("when densification ends (") + what +
              "), remove the least important Gaussians holding this share of the views' "
              "blending weight; 'auto' (the default) holds one training view out and takes the "
              "largest of 0.1, 0.03 and 0.01 that costs it at most --prune-max-loss dB per "
              "halving of the keyframe's bytes, else 0 (0 with fewer than 6 training views)")
      ->check(CLI::IsMember({"auto"}) | m4d::Within(0.0, 0.99));
  command
      ->add_option("--prune-max-loss", args->max_loss_per_halving_db,
                   "dB of the held-out training views an automatic prune share may cost per "
                   "halving of the keyframe's bytes")
      ->check(m4d::Within(0.0, 10.0))
      ->capture_default_str();
}

Status ResolvePruneShare(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                         const PruneShareArguments& args, float* share, PruneShareChoice* choice) {
  *choice = PruneShareChoice();
  if (!args.Automatic()) {
    *share = static_cast<float>(args.share);
    return Status::Ok();
  }
  PruneShareSelectionOptions selection;
  selection.max_loss_per_halving_db = args.max_loss_per_halving_db;
  ProgressBar bar;
  M4D_RETURN_IF_ERROR(SelectPruneShare(
      capture, frame, options, selection,
      [&](const std::string& run, const TrainingProgress& p) {
        bar.Update(p, "prune share test, " + run);
        if (p.iteration == p.iterations) bar.Finish();
      },
      choice));
  PrintChoice(*choice, selection);
  *share = choice->share;
  return Status::Ok();
}

nlohmann::json PruneShareJson(const PruneShareArguments& args, const PruneShareChoice& choice) {
  if (!args.Automatic()) return nullptr;
  auto trial = [](const PruneShareTrial& t) {
    return nlohmann::json{{"share", ShareValue(t.share)},
                          {"gaussians", t.gaussians},
                          {"bytes", t.bytes},
                          {"psnr", t.psnr}};
  };
  nlohmann::json trials = nlohmann::json::array();
  for (const PruneShareTrial& t : choice.trials) trials.push_back(trial(t));
  return {{"max_loss_per_halving_db", args.max_loss_per_halving_db},
          {"validation_cameras", choice.validation_cameras},
          {"unpruned", trial(choice.unpruned)},
          {"trials", trials},
          {"share", ShareValue(choice.share)}};
}

}  // namespace m4d
