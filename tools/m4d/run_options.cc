#include "tools/m4d/run_options.h"

#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "encoder/src/train/densification_strategy.h"
#include "tools/number_checks.h"

namespace m4d {
namespace {

// A --scene-* flag: when given, it sets `field` of whichever built-in scene is generated.
template <typename T>
void AddSceneEdit(CLI::App* command, const std::string& name, T SyntheticSceneOptions::*field,
                  const std::string& help, CaptureArguments* args) {
  command->add_option_function<T>(
      name,
      [args, field](const T& value) {
        args->scene_edits.push_back(
            [field, value](SyntheticSceneOptions* o) { o->*field = value; });
      },
      help);
}

}  // namespace

void AddCaptureArguments(CLI::App* command, CaptureArguments* args) {
  command
      ->add_option("dataset", args->dataset,
                   "N3DV, transforms.json, COLMAP or Dynamic3DGaussians directory, or "
                   "'default' for the built-in synthetic scene, 'realistic' for it with the "
                   "flaws of a real capture")
      ->required();
  command->add_option("--scene-dir", args->scene_dir,
                      "where a built-in scene is generated (default: out/default-scene, "
                      "out/realistic-scene)");
  command
      ->add_option("--test-camera", args->capture.test_camera,
                   "held-out camera index (-1: none; default: the layout's own held-out cameras, "
                   "e.g. test_meta.json, else camera 0 as N3DV)")
      ->check(m4d::Within(-1, 1 << 20));
  command->add_option("--downscale", args->capture.downscale, "integer image downscale factor")
      ->check(m4d::Within(1, 64))
      ->capture_default_str();
  command->add_option("--first-frame", args->capture.first_frame, "first frame to load")
      ->check(m4d::AtLeast(0));
  command->add_option("--frames", args->capture.max_frames, "frames to load (0: all)")
      ->check(m4d::AtLeast(0));
  command->add_option("--initial-points", args->capture.initial_points,
                      "COLMAP sparse model or PLY point cloud for initialisation");
  AddSceneEdit(command, "--scene-cameras", &SyntheticSceneOptions::cameras,
               "built-in scene: cameras (default 16; realistic: 4)", args);
  AddSceneEdit(command, "--scene-width", &SyntheticSceneOptions::width,
               "built-in scene: image width (default 320)", args);
  AddSceneEdit(command, "--scene-height", &SyntheticSceneOptions::height,
               "built-in scene: image height (default 240)", args);
  AddSceneEdit(command, "--scene-frames", &SyntheticSceneOptions::frames,
               "built-in scene: frames (default 20)", args);
  AddSceneEdit(command, "--scene-background-change",
               &SyntheticSceneOptions::background_change_frame,
               "built-in scene: frame of the background change (-1: none)", args);
}

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
  command
      ->add_option("--keyframe-bits-max-loss", args->bits_max_loss_per_halving_db,
                   "with an automatic prune share, the keyframes take the coarsest of the rate "
                   "point's and the coarser points' keyframe bits that costs the same held-out "
                   "views at most this many dB per halving of the keyframe's bytes (0: only bits "
                   "that lose nothing)")
      ->check(m4d::Within(0.0, 10.0))
      ->capture_default_str();
}

void AddRateWeightOption(CLI::App* command, RateWeightArguments* args) {
  command
      ->add_option_function<std::string>(
          "--keyframe-rate-weight",
          [args](const std::string& value) {
            args->automatic = value == "auto";
            args->weight = args->automatic ? -1.0 : std::stod(value);
          },
          "lambda_k: while the first keyframe's training is quantization-aware, its loss gains "
          "this times the bits of the attributes coded as values, per 100 kilobits (default: "
          "the rate point's, 0); 'auto' holds training views out as --prune-share auto does and "
          "takes the largest of 1e-3 and 3e-4 that costs them at most --prune-max-loss dB per "
          "halving of the keyframe's bytes, else 0")
      ->check(CLI::IsMember({"auto"}) | m4d::Within(0.0, 1e3));
}

void AddStrategyOption(CLI::App* command, std::string* name) {
  command
      ->add_option("--strategy", *name,
                   "how keyframe training grows and prunes its Gaussians: 'adc' (the reference "
                   "3DGS's adaptive density control) or 'mcmc' (3DGS as Markov Chain Monte "
                   "Carlo: relocation, an exact budget); default: the schedule's (" +
                       std::string(StrategyName(KeyframeTrainingOptions::Short().strategy)) + ")")
      ->check(CLI::IsMember({"adc", "mcmc"}));
}

void AddSweepOutputOptions(CLI::App* cmd, SweepOutput* out) {
  cmd->add_option("-o,--output-dir", out->dir, "streams, reports and plots go here")
      ->capture_default_str();
  cmd->add_flag("--reuse", out->reuse,
                "take streams whose reports in the output directory record the same options, and "
                "trained keyframes found there, instead of encoding again (to resume a sweep, or "
                "share runs between rd and ablate)");
}

}  // namespace m4d
