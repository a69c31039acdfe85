#include "tools/m4d/encode_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "encoder/src/distributed/chunked_encode.h"
#include "encoder/src/distributed/mpi_ranks.h"
#include "encoder/src/io/atomic_file.h"
#include "encoder/src/pipeline/rate_points.h"
#include "encoder/src/pipeline/sequence_encoder.h"
#include "encoder/src/pipeline/sequence_report_output.h"
#include "encoder/src/run/encode_steps.h"
#include "encoder/src/run/peak_memory.h"
#include "encoder/src/run/rendition_encode.h"
#include "encoder/src/run/strategy_arguments.h"
#include "encoder/src/run/stream_check.h"
#include "encoder/src/run/view_strip.h"
#include "encoder/src/stream/frame_rate.h"
#include "encoder/src/video/video_writer.h"
#include "tools/m4d/command_status.h"
#include "tools/m4d/rate_point_name.h"
#include "tools/m4d/run_options.h"
#include "tools/number_checks.h"

namespace m4d {

void AddEncoderOptions(CLI::App* cmd, EncodeArguments* a) {
  EncoderOptions& o = a->encoder;
  CLI::Option* lambda =
      cmd->add_option("--lambda", a->lambda,
                      "rate weight lambda_2 of motion estimation; the other settings are those "
                      "of the rate point with the nearest lambda_2")
          ->check(m4d::AtLeast(0))
          ->capture_default_str();
  cmd->add_option("--rate-point", a->rate_point,
                  "named rate point r1 (fewest bytes) .. r5: lambda_2 = 5e-4, 3e-4, 2e-4, "
                  "1e-4, 5e-5, with tau_g and bit depths (docs/encoder.md)")
      ->check(RatePointName())
      ->excludes(lambda);
  cmd->add_option("--sh-degree", o.sh_degree, "SH degree of the stream")
      ->check(m4d::Within(0, 3))
      ->capture_default_str();
  cmd->add_option("--keyframe-iterations", a->keyframe_iterations,
                  "first keyframe's training (the short schedule scaled; default 7000)")
      ->check(m4d::Positive());
  cmd->add_option("--keyframe-ply", a->keyframe_ply,
                  "start from this trained first keyframe (a 3DGS PLY, e.g. from m4d train) "
                  "instead of training it")
      ->check(CLI::ExistingFile);
  cmd->add_option("--max-gaussians", a->max_gaussians,
                  "at most this many Gaussians after densification (keyframes and retraining; "
                  "default: the schedule's 1000000)")
      ->check(m4d::Within(1, 1000000));
  cmd->add_option("--gaussians-per-pixel", a->gaussians_per_pixel,
                  "at most this many Gaussians per pixel of the training views (keyframes and "
                  "retraining; 0: no such cap; default 0.25)")
      ->check(m4d::Within(0.0, 64.0));
  cmd->add_option("--quantization-aware", a->quantization_aware,
                  "the last N iterations of the first keyframe's training render it as coded "
                  "(default: a quarter of the run; retraining: a quarter of its run; 0: none)")
      ->check(m4d::AtLeast(0));
  AddPruneShareOptions(
      cmd,
      "keyframes and retraining; with --keyframe-ply chosen too when later GOPs retrain theirs",
      &a->prune);
  cmd->add_option("--prune-below", a->prune_below,
                  "when densification ends (keyframes and retraining), remove the Gaussians "
                  "whose blending weight summed over the views is below this many pixels "
                  "(default 0.05; 0: none)")
      ->check(m4d::Within(0.0, 1e6));
  AddStrategyOption(cmd, &a->strategy);
  cmd->add_flag("--random-init", a->random_init,
                "without initial points, start the first keyframe at random in the part of "
                "the cameras' box two views see instead of from photo-consistent points");
  cmd->add_option("--retrain-iterations", o.retrain_iterations, "later keyframes' retraining")
      ->check(m4d::Positive())
      ->capture_default_str();
  cmd->add_option("--lookahead", o.lookahead_frames, "frames from a keyframe to t1")
      ->check(m4d::Positive())
      ->capture_default_str();
  cmd->add_option("--lookahead-step", o.lookahead_step,
                  "frames between the lookahead's fine-tuning steps")
      ->check(m4d::Positive())
      ->capture_default_str();
  cmd->add_option("--tau-delta", o.decoupling.thresholds.displacement,
                  "decoupling: projected displacement threshold (our units, see docs/encoder.md)")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_option("--tau-s", o.decoupling.thresholds.scale_change,
                  "decoupling: log-scale change threshold")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_option("--tau-e", o.decoupling.thresholds.error,
                  "decoupling: error threshold of the refinement (mean absolute error in [0, 1])")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_option("--change-support", o.decoupling.thresholds.change_support,
                  "decoupling: share of a Gaussian's blend weight that must lie on pixels changed "
                  "beyond the noise for it to be dynamic (0: the paper's rule)")
      ->check(m4d::Within(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--motion-iterations", o.motion.iterations, "motion estimation per frame")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--first-motion-iterations", o.first_motion_iterations,
                  "motion estimation of a GOP's first inter frame, which also trains the MLP")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--motion-rate-decay", o.motion_rate_decay,
                  "share of lambda_2 the motion rate weight falls per inter frame of a GOP, "
                  "down to 0.3 of it (0: constant)")
      ->check(m4d::Within(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--motion-views-per-step", o.motion.views_per_step,
                  "training views averaged in each motion estimation step")
      ->check(m4d::Positive())
      ->capture_default_str();
  cmd->add_option("--compensation-iterations", o.compensation.iterations,
                  "compensation training per frame")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--lambda3", a->lambda3,
                  "sparsity weight lambda_3 of compensation (default 5e-5)")
      ->check(m4d::AtLeast(0));
  cmd->add_option("--tau-g", a->tau_g,
                  "compensation: view-space gradient above which a Gaussian is replicated "
                  "(default: the rate point's)")
      ->check(m4d::AtLeast(0));
  cmd->add_option("--compensation-min-gain", o.compensation_min_gain,
                  "code a frame's compensation only when it raises the training views' PSNR by "
                  "this many dB (negative: always, as the paper)")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_flag(
      "--no-early-compensation-decision", [&o](int64_t) { o.compensation_early_decision = false; },
      "train every frame's compensation to its last step, even when its gain is on course to "
      "stay under --compensation-min-gain");
  cmd->add_option("--motion-min-gain", o.motion_min_gain,
                  "code a frame's motion only when it raises the training views' PSNR by more "
                  "than this many dB over showing the previous frame again (negative: always)")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_option("--appearance-step", o.motion.appearance_step,
                  "quantization step of the dynamic Gaussians' colour change per inter frame, in "
                  "SH DC units (0: colours stay the keyframe's for the whole GOP, as the paper)")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--appearance-min-gain", o.appearance_min_gain,
                  "code a frame's colour change only when it raises the PSNR of the training views "
                  "that did not train it (--appearance-check-every) by more than this many dB "
                  "(negative: always)")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_option("--appearance-gain-per-doubling", o.appearance_gain_per_doubling,
                  "and by more than this many dB per doubling of the frame's bytes that it causes "
                  "(0: any gain above --appearance-min-gain)")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--appearance-check-every", o.motion.appearance_check_every,
                  "every this many-th training view trains no colour change and judges it (0: "
                  "every view trains it, and all judge it)")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--appearance-min-views", o.appearance_min_views,
                  "train the colour change only with at least this many training views")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_flag("!--no-noise-gap", o.gop.noise_gap,
                "the quality guard compares with the keyframe's training PSNR itself, not less "
                "its noise gap");
  cmd->add_option("--gop-threshold", o.gop.threshold, "tau_GOP of the adaptive GOP")
      ->check(m4d::Finite())
      ->capture_default_str();
  cmd->add_option("--gop-psnr-drop", o.gop.max_psnr_drop,
                  "a new GOP when the training views' PSNR falls this many dB below the "
                  "keyframe's (0: off)")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  cmd->add_option("--fixed-gop", o.gop.fixed_length,
                  "fixed GOP of this many frames instead of the adaptive GOP")
      ->check(m4d::AtLeast(0));
  cmd->add_option("--max-gop", o.gop.max_length, "longest GOP")
      ->check(m4d::Positive())
      ->capture_default_str();
  cmd->add_option("--random-access", o.gop.random_access_seconds,
                  "seconds of content between random-access keyframes; a GOP started in between "
                  "keeps the static layer and re-sends the dynamic layer only (0: every GOP is a "
                  "random-access point)")
      ->check(m4d::Within(0.0, 1e6))
      ->capture_default_str();
  cmd->add_flag(
      "--no-decoupling", [&o](int64_t) { o.ablation.decoupling = false; },
      "ablation: every Gaussian dynamic");
  cmd->add_flag(
      "--no-motion", [&o](int64_t) { o.ablation.motion_estimation = false; },
      "ablation: no motion estimation (zero grids)");
  cmd->add_flag(
      "--no-compensation", [&o](int64_t) { o.ablation.compensation = false; },
      "ablation: no Gaussian compensation");
  cmd->add_flag(
      "--no-rate", [&o](int64_t) { o.ablation.rate_term = false; },
      "ablation: motion trained without the rate term");
  cmd->add_flag("--independent-frames", o.independent_frames,
                "baseline: every frame trained from scratch and coded as a static keyframe");
  cmd->add_option("--keyframe-bits", a->keyframe_bits,
                  "keyframe Gaussians' bits: position,scale,rotation,opacity,color,sh "
                  "(default: the rate point's)")
      ->expected(6)
      ->delimiter(',')
      ->check(m4d::Within(1, 24));
  cmd->add_option("--compensation-bits", a->compensation_bits,
                  "compensated Gaussians' bits: position,scale,rotation,opacity,color,sh "
                  "(default: the rate point's)")
      ->expected(6)
      ->delimiter(',')
      ->check(m4d::Within(1, 24));
  cmd->add_option("--keyframe-codebooks", a->keyframe_codebooks,
                  "keyframe Gaussians' codebook sizes: scale,color,sh (0: scalar values; "
                  "default: the rate point's)")
      ->expected(3)
      ->delimiter(',')
      ->check(m4d::Within(0, 4096));
  AddRateWeightOption(cmd, &a->keyframe_rate);
  cmd->add_option("--threads", o.context.threads, "threads (0: all cores)")->check(m4d::AtLeast(0));
  cmd->add_option("--seed", o.context.seed, "random seed")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
}

void AddEncodeCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<EncodeArguments>();
  CLI::App* cmd = app->add_subcommand("encode", "encode a multi-view video into an M4D stream");
  AddCaptureArguments(cmd, &args->capture);
  AddEncoderOptions(cmd, args.get());
  cmd->add_option("-o,--output", args->output, "stream file")->capture_default_str();
  cmd->add_option("--fps", args->fps,
                  "frame rate written into the stream: 30, 29.97 or 30000/1001 (default: the "
                  "capture's, else 30)");
  cmd->add_option("--up", args->up,
                  "the world's up axis the stream states, for players and exporters: +x, -x, "
                  "+y, -y, +z, -z, none, or auto: the capture cameras' mean up, snapped to an "
                  "axis")
      ->check(CLI::IsMember({"auto", "none", "+x", "-x", "+y", "-y", "+z", "-z"}))
      ->capture_default_str();
  cmd->add_option("--json", args->json, "report file (default: the stream's name + .json)");
  cmd->add_option("--views", args->views,
                  "write the held-out view, its decoded render and their difference (x4), one PNG "
                  "per frame and views.mp4 of them all, here");
  cmd->add_option("--chunk-frames", args->chunk_frames,
                  "code the frames in chunks of this many, each from a random-access keyframe, "
                  "checkpointed and spread over the ranks of an MPI job (default under MPI: the "
                  "frames over the ranks)")
      ->check(m4d::Positive());
  cmd->add_option("--checkpoint-dir", args->checkpoint_dir,
                  "finished chunks, kept for a resumed run (default: the stream's name + "
                  ".chunks; under MPI on a file system every rank sees)");
  cmd->add_option("--max-chunks", args->max_chunks,
                  "stop after coding this many chunks (per rank); the same command resumes")
      ->check(m4d::Positive());
  cmd->add_option("--renditions", args->renditions,
                  "rate points (e.g. r1,r3,r5) coded as renditions from one first keyframe with "
                  "aligned GOPs, the first deciding the GOPs: OUT.r1.m4d ... beside -o OUT.m4d, "
                  "and OUT.manifest.json listing them for adaptive bitrate")
      ->delimiter(',')
      ->check(RatePointName())
      ->excludes("--lambda");
  auto overwrite = std::make_shared<bool>(false);
  cmd->add_flag("-f,--force", *overwrite, "replace an existing stream (else refused)");
  cmd->callback([args, overwrite, exit_code]() {
    if (!args->renditions.empty()) {
      const Status checked = CheckRenditionOutputs(*args, *overwrite);
      *exit_code = checked.ok() ? ReportStatus("encode", RunRenditionEncode(*args, *overwrite))
                                : 2 * ReportStatus("encode", checked);  // before any work
      return;
    }
    std::error_code ec;
    if (!*overwrite && std::filesystem::is_regular_file(args->output, ec)) {
      ReportStatus("encode",
                   Status(M4D_ERR_INVALID_ARG,
                          args->output + " exists: give --force to replace it, or another -o"));
      *exit_code = 2;  // found before any work, from the command line
      return;
    }
    SequenceReport report;
    *exit_code = ReportStatus("encode", RunEncode(*args, &report));
  });
}

}  // namespace m4d
