// The dataset argument every m4d command takes: a directory in any supported layout, or
// "default" for the built-in synthetic scene (generated into --scene-dir on first use).
#ifndef M4D_TOOLS_M4D_CAPTURE_ARGUMENTS_H_
#define M4D_TOOLS_M4D_CAPTURE_ARGUMENTS_H_

#include <CLI/CLI.hpp>
#include <string>

#include "common/status.h"
#include "dataset/capture.h"
#include "dataset/capture_options.h"
#include "synthetic_scene/synthetic_scene_options.h"

namespace m4d {

struct CaptureArguments {
  std::string dataset = "default";
  std::string scene_dir = "out/default-scene";
  CaptureOptions capture;
  SyntheticSceneOptions scene;
};

// Adds DATASET and the loading options to a command.
void AddCaptureArguments(CLI::App* command, CaptureArguments* args);

// Loads the dataset (generating the default scene first if needed), printing what it does.
Status OpenCapture(const CaptureArguments& args, Capture* capture);

// CheckCaptureViews (dataset/capture_check.h) over the frames a command will use, before any
// training; says on stderr that they passed.
Status CheckViewsBeforeTraining(const Capture& capture, int first_frame, int frame_count);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_CAPTURE_ARGUMENTS_H_
