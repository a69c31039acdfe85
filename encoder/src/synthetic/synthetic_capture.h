// The synthetic scene straight into a Capture, without files: every view is rendered up
// front and kept as 8-bit RGB in memory (the same samples the PNG or JPEG files of
// WriteSyntheticScene decode to), with the rig's calibration (mirrored when left-handed),
// camera 0 held out and the initial point cloud. With lens distortion the views are served
// undistorted to pinhole cameras, as the transforms.json loader serves the files.
#ifndef M4D_ENCODER_SYNTHETIC_SYNTHETIC_CAPTURE_H_
#define M4D_ENCODER_SYNTHETIC_SYNTHETIC_CAPTURE_H_

#include <cstddef>

#include "encoder/src/capture/capture.h"
#include "encoder/src/synthetic/scene_writer.h"
#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Most bytes of images the in-memory capture holds; larger scenes go through files.
constexpr size_t kMaxSyntheticCaptureBytes = size_t{1} << 30;

// Errors as WriteSyntheticScene's, and M4D_ERR_LIMIT when the images would exceed
// kMaxSyntheticCaptureBytes.
Status GenerateSyntheticCapture(const SyntheticSceneOptions& options, Capture* capture,
                                const SceneProgress& progress = nullptr);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SYNTHETIC_CAPTURE_H_
