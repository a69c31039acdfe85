#include "tools/m4d/prune_share_arguments.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "encoder/src/train/progress_bar.h"
#include "tools/number_checks.h"

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

void PrintStartSize(const StartSizeChoice& choice) {
  if (choice.trials.empty()) return;
  std::string cameras;
  for (int c : choice.validation_cameras) cameras += " " + std::to_string(c);
  std::printf("start size selection         cameras%s held out, the unpruned branches\n",
              cameras.c_str());
  std::printf("  %-16s %8s %10s  %11s  %9s  %9s\n", "run", "start", "Gaussians", "coded",
              "held out", "score");
  for (const StartSizeTrial& t : choice.trials) {
    char run[32];
    std::snprintf(run, sizeof(run), "sweep share %g", static_cast<double>(t.sweep_share));
    std::printf("  %-16s %8zu %10zu  %8.1f KB  %6.2f dB  %6.2f dB%s\n", run, t.start_points,
                t.gaussians, t.bytes / 1000.0, t.psnr, t.score,
                t.sweep_share == choice.sweep_share ? "  chosen" : "");
  }
  std::printf("sweep share                  %g\n", static_cast<double>(choice.sweep_share));
}

SelectionProgress BarProgress(ProgressBar* bar, const std::string& what) {
  return [bar, what](const std::string& run, const TrainingProgress& p) {
    bar->Update(p, what + ", " + run);
    if (p.iteration == p.iterations) bar->Finish();
  };
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
          "--start-share",
          [args](const std::string& value) {
            args->sweep_share = value == "auto" ? -1.0 : std::stod(value);
          },
          "without initial points, ask the photo-consistent sweep for this share of the start's "
          "points; 'auto' (the default) holds training views out as --prune-share auto does and "
          "takes the best of 1 and 0.1, each scored by its held-out PSNR plus --prune-max-loss "
          "dB per halving of the keyframe's bytes (1 with fewer than 6 training views)")
      ->check(CLI::IsMember({"auto"}) | m4d::Within(0.001, 1.0));
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
                   "dB of the held-out training views an automatic prune share or start share "
                   "may cost per halving of the keyframe's bytes")
      ->check(m4d::Within(0.0, 10.0))
      ->capture_default_str();
}

Status ResolveKeyframeShares(const Capture& capture, int frame, const PruneShareArguments& args,
                             KeyframeTrainingOptions* options, KeyframeShareChoice* choice) {
  *choice = KeyframeShareChoice();
  if (!args.StartAutomatic()) options->sweep_share = static_cast<float>(args.sweep_share);
  if (!args.Automatic()) options->importance_prune_share = static_cast<float>(args.share);
  PruneShareSelectionOptions selection;
  selection.max_loss_per_halving_db = args.max_loss_per_halving_db;
  ProgressBar bar;
  PruneShareTrunk trunk;
  if (args.StartAutomatic()) {
    StartSizeSelectionOptions start;
    start.held_out = selection;
    M4D_RETURN_IF_ERROR(SelectStartSize(capture, frame, *options, start,
                                        BarProgress(&bar, "start size test"), &choice->start,
                                        &trunk));
    PrintStartSize(choice->start);
    options->sweep_share = choice->start.sweep_share;
  }
  if (!args.Automatic()) return Status::Ok();
  const SelectionProgress progress = BarProgress(&bar, "prune share test");
  if (choice->start.trials.empty()) {
    M4D_RETURN_IF_ERROR(
        SelectPruneShare(capture, frame, *options, selection, progress, &choice->prune));
  } else {
    M4D_RETURN_IF_ERROR(SelectPruneShare(trunk, selection, progress, &choice->prune));
  }
  PrintChoice(choice->prune, selection);
  options->importance_prune_share = choice->prune.share;
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

nlohmann::json StartSizeJson(const PruneShareArguments& args, const StartSizeChoice& choice) {
  if (!args.StartAutomatic()) return nullptr;
  nlohmann::json trials = nlohmann::json::array();
  for (const StartSizeTrial& t : choice.trials) {
    trials.push_back({{"sweep_share", ShareValue(t.sweep_share)},
                      {"start_points", t.start_points},
                      {"gaussians", t.gaussians},
                      {"bytes", t.bytes},
                      {"psnr", t.psnr},
                      {"score", t.score}});
  }
  return {{"validation_cameras", choice.validation_cameras},
          {"trials", trials},
          {"sweep_share", ShareValue(choice.sweep_share)}};
}

}  // namespace m4d
