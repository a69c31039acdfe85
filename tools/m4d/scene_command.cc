#include "scene_command.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "command_status.h"
#include "synthetic_scene/scene_writer.h"

namespace m4d {

void AddSceneCommand(CLI::App* app, int* exit_code) {
  struct Arguments {
    SyntheticSceneOptions scene;
    std::string output = "out/default-scene";
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* cmd = app->add_subcommand("scene", "write the built-in synthetic scene");
  SyntheticSceneOptions& s = args->scene;
  cmd->add_option("-o,--output", args->output, "directory")->capture_default_str();
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
  cmd->add_option("--seed", s.seed, "layout and texture seed")->capture_default_str();
  cmd->callback([args, exit_code]() {
    const auto start = std::chrono::steady_clock::now();
    Status status = WriteSyntheticScene(args->scene, args->output, [](int done, int count) {
      std::fprintf(stderr, "\rrendering frame %d/%d", done, count);
      if (done == count) std::fprintf(stderr, "\n");
    });
    if (status.ok()) {
      std::printf("scene written to %s in %.1f s\n", args->output.c_str(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    *exit_code = ReportStatus("scene", status);
  });
}

}  // namespace m4d
