// LoadCapture: opens a multi-view capture of any supported layout, recognised by the files
// present (in this order of precedence):
//   transforms.json   nerfstudio (nerfstudio_loader.h); `path` may also be the JSON file;
//   poses_bounds.npy  N3DV (n3dv_loader.h);
//   train_meta.json   Dynamic 3D Gaussians (dynamic3dgs_loader.h);
//   sparse/0, sparse or cameras.bin|txt   COLMAP (colmap_loader.h).
// Images load lazily through Capture::frames; the options apply as capture_options.h says.
#ifndef M4D_ENCODER_DATASET_CAPTURE_LOADER_H_
#define M4D_ENCODER_DATASET_CAPTURE_LOADER_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/capture_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

// The layout name LoadCapture would use ("nerfstudio", "n3dv", "dynamic3dgs", "colmap"),
// or M4D_ERR_INVALID_ARG when none is recognised.
Status DetectCaptureLayout(const std::string& path, std::string* layout);

Status LoadCapture(const std::string& path, const CaptureOptions& options, Capture* capture);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_CAPTURE_LOADER_H_
