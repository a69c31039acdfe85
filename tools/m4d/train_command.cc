#include "tools/m4d/train_command.h"

#include <memory>
#include <string>

#include "encoder/src/run/train_run.h"
#include "tools/existing_output.h"
#include "tools/m4d/command_status.h"
#include "tools/m4d/rate_point_name.h"
#include "tools/m4d/run_options.h"
#include "tools/number_checks.h"

namespace m4d {

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
