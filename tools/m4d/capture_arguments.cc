#include "capture_arguments.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "dataset/capture_check.h"
#include "dataset/capture_loader.h"
#include "synthetic_scene/scene_writer.h"

namespace m4d {

void AddCaptureArguments(CLI::App* command, CaptureArguments* args) {
  command
      ->add_option("dataset", args->dataset,
                   "N3DV, transforms.json, COLMAP or Dynamic3DGaussians directory, or "
                   "'default' for the built-in synthetic scene")
      ->capture_default_str();
  command->add_option("--scene-dir", args->scene_dir, "where the default scene is generated")
      ->capture_default_str();
  command
      ->add_option("--test-camera", args->capture.test_camera,
                   "held-out camera index (-1: none; default: the layout's own held-out cameras, "
                   "e.g. test_meta.json, else camera 0 as N3DV)")
      ->check(CLI::Range(-1, 1 << 20));
  command->add_option("--downscale", args->capture.downscale, "integer image downscale factor")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--first-frame", args->capture.first_frame, "first frame to load")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--frames", args->capture.max_frames, "frames to load (0: all)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--initial-points", args->capture.initial_points,
                      "COLMAP sparse model or PLY point cloud for initialisation");
  command->add_option("--scene-cameras", args->scene.cameras, "default scene: cameras")
      ->capture_default_str();
  command->add_option("--scene-width", args->scene.width, "default scene: image width")
      ->capture_default_str();
  command->add_option("--scene-height", args->scene.height, "default scene: image height")
      ->capture_default_str();
  command->add_option("--scene-frames", args->scene.frames, "default scene: frames")
      ->capture_default_str();
  command->add_option("--scene-background-change", args->scene.background_change_frame,
                      "default scene: frame of the background change (-1: none)");
}

Status OpenCapture(const CaptureArguments& args, Capture* capture) {
  std::string path = args.dataset;
  if (args.dataset == "default") {
    path = args.scene_dir;
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::path(path) / "transforms.json", ec)) {
      std::fprintf(stderr, "generating the default scene into %s\n", path.c_str());
      const auto start = std::chrono::steady_clock::now();
      M4D_RETURN_IF_ERROR(WriteSyntheticScene(args.scene, path, [](int done, int count) {
        std::fprintf(stderr, "\r  frame %d/%d", done, count);
        if (done == count) std::fprintf(stderr, "\n");
      }));
      std::fprintf(stderr, "  done in %.1f s\n",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    } else {
      std::fprintf(stderr, "using the default scene in %s (delete it to regenerate)\n",
                   path.c_str());
    }
  }
  M4D_RETURN_IF_ERROR(LoadCapture(path, args.capture, capture));
  std::fprintf(stderr, "%s: %s layout, %d cameras, %d frames, %dx%d, %zu initial points\n",
               path.c_str(), capture->layout.c_str(), capture->camera_count(), capture->frame_count,
               capture->camera_count() ? capture->camera(0, 0).width : 0,
               capture->camera_count() ? capture->camera(0, 0).height : 0,
               capture->initial_points.size());
  for (const std::string& note : capture->notes) std::fprintf(stderr, "  note: %s\n", note.c_str());
  if (!capture->test_cameras.empty()) {
    std::string names;
    for (int c : capture->test_cameras) names += " " + capture->camera_names[c];
    std::fprintf(stderr, "  held-out cameras:%s\n", names.c_str());
  }
  return Status::Ok();
}

Status CheckViewsBeforeTraining(const Capture& capture, int first_frame, int frame_count) {
  const auto start = std::chrono::steady_clock::now();
  M4D_RETURN_IF_ERROR(CheckCaptureViews(capture, first_frame, frame_count));
  std::fprintf(stderr, "  every view of the frames to code decodes at its size (%.1f s)\n",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return Status::Ok();
}

}  // namespace m4d
