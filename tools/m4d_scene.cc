// m4d_scene: writes the built-in synthetic multi-view scene (a textured room, a walking
// figure, a spinning cube, a ball that appears mid-sequence, optionally a lamp that changes
// colour) to a directory: images/camXX/NNNNNN.png, transforms.json, points3d.ply, scene.json.
// Renders headless with OpenGL ES through EGL; no GPU needed.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <string>

#include "synthetic_scene/scene_writer.h"

int main(int argc, char** argv) {
  m4d::SyntheticSceneOptions opt;
  std::string output = "scene";
  bool quiet = false;
  CLI::App app{"Write the built-in synthetic multi-view dynamic scene to a directory."};
  app.add_option("-o,--output", output, "directory to write (created when missing)");
  app.add_option("--cameras", opt.cameras, "cameras in the rig; camera 0 is held out")
      ->check(CLI::Range(1, m4d::kMaxSyntheticCameras));
  app.add_option("--width", opt.width, "image width")->check(CLI::Range(8, m4d::kMaxSyntheticSide));
  app.add_option("--height", opt.height, "image height")
      ->check(CLI::Range(8, m4d::kMaxSyntheticSide));
  app.add_option("--frames", opt.frames, "frames")->check(CLI::Range(1, m4d::kMaxSyntheticFrames));
  app.add_option("--fov", opt.horizontal_fov_degrees, "horizontal field of view, degrees")
      ->check(CLI::Range(11.0f, 149.0f));
  app.add_option("--emergent-frame", opt.emergent_frame,
                 "frame at which the ball appears (-1: frames / 2)");
  app.add_option("--background-change-frame", opt.background_change_frame,
                 "frame at which the lamp changes colour (-1: never)");
  app.add_option("--seed", opt.seed, "seed of textures, book layout and point sampling");
  app.add_option("--points", opt.points, "points in points3d.ply")
      ->check(CLI::Range(0, m4d::kMaxSyntheticPoints));
  app.add_option("--supersample", opt.supersample, "render at this multiple, then filter down")
      ->check(CLI::Range(1, 4));
  app.add_option("--msaa", opt.msaa_samples, "multisamples of the render (1: none)")
      ->check(CLI::Range(1, 16));
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  CLI11_PARSE(app, argc, argv);

  const auto t0 = std::chrono::steady_clock::now();
  const m4d::Status status = m4d::WriteSyntheticScene(opt, output, [quiet](int done, int total) {
    if (!quiet) std::fprintf(stderr, "\rm4d_scene: rendered frame %d / %d", done, total);
  });
  if (!quiet) std::fprintf(stderr, "\n");
  if (!status.ok()) {
    std::fprintf(stderr, "m4d_scene: %s\n", status.message().c_str());
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("m4d_scene: %d cameras x %d frames at %dx%d written to %s in %.1f s\n", opt.cameras,
              opt.frames, opt.width, opt.height, output.c_str(), seconds);
  return 0;
}
