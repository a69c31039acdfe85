// The dataset argument every m4d command takes: a directory in any supported layout, or
// "default" or "realistic" for the built-in synthetic scene, clean or with the flaws of a
// real capture (generated into --scene-dir on first use).
#ifndef M4D_ENCODER_RUN_CAPTURE_ARGUMENTS_H_
#define M4D_ENCODER_RUN_CAPTURE_ARGUMENTS_H_

#include <functional>
#include <string>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/capture_options.h"
#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct CaptureArguments {
  std::string dataset;    // required: a bare command must not start hours of work
  std::string scene_dir;  // empty: out/<dataset>-scene for a built-in scene
  CaptureOptions capture;
  // What the --scene-* flags change in the built-in scene's options, in order.
  std::vector<std::function<void(SyntheticSceneOptions*)>> scene_edits;
};

// Loads the dataset (generating a built-in scene first if needed), printing what it does.
Status OpenCapture(const CaptureArguments& args, Capture* capture);

// CheckCaptureViews (dataset/capture_check.h) over the frames a command will use, before any
// training; says on stderr that they passed.
Status CheckViewsBeforeTraining(const Capture& capture, int first_frame, int frame_count);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_CAPTURE_ARGUMENTS_H_
