#include "tools/m4d/scene_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "encoder/src/synthetic/scene_writer.h"
#include "encoder/src/train/progress_bar.h"
#include "tools/m4d/command_status.h"
#include "tools/number_checks.h"

namespace m4d {
namespace {

// The CaptureRealism flags. Defined after --realistic, so that they override its preset
// (CLI11 applies options in the order they are defined).
void AddRealismOptions(CLI::App* cmd, CaptureRealism* r) {
  cmd->add_option("--noise", r->noise_sigma, "sensor noise sigma, 8-bit levels (0: none)")
      ->capture_default_str();
  cmd->add_option("--jpeg-quality", r->jpeg_quality, "write JPEGs of this quality (0: PNG)")
      ->capture_default_str();
  cmd->add_option("--exposure-spread", r->exposure_spread,
                  "per-camera gain 1 +- this (0: all alike)")
      ->capture_default_str();
  cmd->add_option("--white-balance-spread", r->white_balance_spread,
                  "per-camera, per-channel gain 1 +- this (0: neutral)")
      ->capture_default_str();
  cmd->add_option("--k1", r->k1, "radial distortion k1 (OpenCV model)")->capture_default_str();
  cmd->add_option("--k2", r->k2, "radial distortion k2")->capture_default_str();
  cmd->add_option("--p1", r->p1, "tangential distortion p1")->capture_default_str();
  cmd->add_option("--p2", r->p2, "tangential distortion p2")->capture_default_str();
  cmd->add_flag("--left-handed,!--right-handed", r->left_handed,
                "write the world mirrored in x (rotations of determinant -1)");
  cmd->add_flag("--sparse-rig,!--row-rig", r->sparse_rig,
                "cameras on one wide arc instead of front-facing rows");
  cmd->add_option("--sparse-rig-arc", r->sparse_rig_arc_degrees, "sparse rig's arc, degrees")
      ->capture_default_str();
  cmd->add_option("--background-sway", r->background_sway,
                  "a plant at the back sways this much, metres (0: no plant)")
      ->capture_default_str();
  cmd->add_option("--light-flicker", r->light_flicker,
                  "lights' strength varies by +- this every frame (0: steady)")
      ->capture_default_str();
}

}  // namespace

void AddSceneCommand(CLI::App* app, int* exit_code) {
  struct Arguments {
    SyntheticSceneOptions scene;
    std::string output;
    bool force = false;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* cmd = app->add_subcommand("scene", "write the built-in synthetic scene");
  SyntheticSceneOptions& s = args->scene;
  // Required: a bare command writes nothing (encode and train generate a built-in scene
  // themselves when they need one).
  cmd->add_option("-o,--output", args->output, "directory to write the scene into")->required();
  cmd->add_flag_callback(
      "--realistic", [args]() { args->scene = SyntheticSceneOptions::Realistic(); },
      "the realistic preset: every flaw below on, a sparse rig of 4 cameras; the options "
      "below override it");
  cmd->add_option("--cameras", s.cameras, "cameras of the rig")->capture_default_str();
  cmd->add_option("--width", s.width, "image width")->capture_default_str();
  cmd->add_option("--height", s.height, "image height")->capture_default_str();
  cmd->add_option("--frames", s.frames, "frames")->capture_default_str();
  cmd->add_option("--emergent-frame", s.emergent_frame,
                  "frame where the new object appears (-1: half way)")
      ->capture_default_str();
  cmd->add_option("--background-change", s.background_change_frame,
                  "frame where the lamp changes the background (-1: never)")
      ->capture_default_str();
  cmd->add_option("--points", s.points, "initial points")->capture_default_str();
  cmd->add_option("--seed", s.seed, "layout, texture and realism seed")
      ->check(m4d::AtLeast(0))
      ->capture_default_str();
  AddRealismOptions(cmd, &s.realism);
  cmd->add_flag("-f,--force", args->force, "write into a folder that already holds files");
  cmd->callback([args, exit_code]() {
    std::error_code ec;
    if (!args->force && std::filesystem::is_directory(args->output, ec) &&
        !std::filesystem::is_empty(args->output, ec)) {
      ReportStatus("scene", Status(M4D_ERR_INVALID_ARG,
                                   args->output + " holds files: give --force to write over them"));
      *exit_code = 2;  // found before any work, from the command line
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    Status status = WriteSyntheticScene(args->scene, args->output, [](int done, int count) {
      ShowStatus(stderr, "rendering frame " + std::to_string(done) + "/" + std::to_string(count));
      if (done == count) ClearStatus(stderr);
    });
    if (status.ok()) {
      std::printf("scene written to %s in %.1f s\n", args->output.c_str(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    *exit_code = ReportStatus("scene", status);
  });
}

}  // namespace m4d
