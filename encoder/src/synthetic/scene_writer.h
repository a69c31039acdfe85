// Writing the synthetic scene to a directory in the transforms.json layout (README.md here):
// images/<camera>/<frame>.png (.jpg with CaptureRealism::jpeg_quality) for every view,
// transforms.json, points3d.ply and scene.json (what happens when, and every option).
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_WRITER_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_WRITER_H_

#include <functional>
#include <string>

#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Called after each frame's views are rendered: frames_done of frame_count.
using SceneProgress = std::function<void(int frames_done, int frame_count)>;

// Creates `dir` (and its parents) when missing and replaces files of the same names. Errors:
// bad options, no GL, or a file that cannot be written (M4D_ERR_INVALID_ARG with the path).
Status WriteSyntheticScene(const SyntheticSceneOptions& options, const std::string& dir,
                           const SceneProgress& progress = nullptr);

// Relative path of a view's image: "images/cam03/000012.png", or ".jpg" when `jpeg`.
std::string SyntheticImagePath(const std::string& camera_name, int frame, bool jpeg = false);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_WRITER_H_
