#include "encoder/src/run/capture_arguments.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "encoder/src/dataset/capture_check.h"
#include "encoder/src/dataset/capture_loader.h"
#include "encoder/src/synthetic/scene_writer.h"
#include "encoder/src/train/progress_bar.h"

namespace m4d {
namespace {

// The built-in scene a dataset name stands for; false for any other name.
bool BuiltInScene(const CaptureArguments& args, SyntheticSceneOptions* options) {
  if (args.dataset == "default") {
    *options = SyntheticSceneOptions();
  } else if (args.dataset == "realistic") {
    *options = SyntheticSceneOptions::Realistic();
  } else {
    return false;
  }
  for (const auto& edit : args.scene_edits) edit(options);
  return true;
}

}  // namespace

Status OpenCapture(const CaptureArguments& args, Capture* capture) {
  std::string path = args.dataset;
  SyntheticSceneOptions scene;
  if (BuiltInScene(args, &scene)) {
    path = args.scene_dir.empty() ? "out/" + args.dataset + "-scene" : args.scene_dir;
    std::error_code ec;
    if (!std::filesystem::exists(std::filesystem::path(path) / "transforms.json", ec)) {
      std::fprintf(stderr, "generating the %s scene into %s\n", args.dataset.c_str(), path.c_str());
      const auto start = std::chrono::steady_clock::now();
      M4D_RETURN_IF_ERROR(WriteSyntheticScene(scene, path, [](int done, int count) {
        ShowStatus(stderr, "  frame " + std::to_string(done) + "/" + std::to_string(count));
        if (done == count) ClearStatus(stderr);
      }));
      std::fprintf(stderr, "  done in %.1f s\n",
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    } else {
      std::fprintf(stderr, "using the %s scene in %s (delete it to regenerate)\n",
                   args.dataset.c_str(), path.c_str());
    }
  }
  M4D_RETURN_IF_ERROR(LoadCapture(path, args.capture, capture));
  std::fprintf(stderr, "%s: %s layout, %d cameras, %d frames, %dx%d, %zu initial points\n",
               path.c_str(), capture->layout.c_str(), capture->camera_count(), capture->frame_count,
               capture->camera_count() ? capture->camera(0, 0).width : 0,
               capture->camera_count() ? capture->camera(0, 0).height : 0,
               capture->initial_points.size());
  for (const std::string& note : capture->notes) std::fprintf(stderr, "  note: %s\n", note.c_str());
  // Fewer frames than asked is no error (a capture's length is seldom known by heart), but it
  // is said: the report would otherwise look complete.
  if (args.capture.max_frames > capture->frame_count) {
    std::fprintf(stderr, "warning: --frames %d, but the capture has %d from frame %d: coding %d\n",
                 args.capture.max_frames, capture->frame_count, args.capture.first_frame,
                 capture->frame_count);
  }
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
