#include "encoder/src/run/prune_share_arguments.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "encoder/src/train/progress_bar.h"

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
