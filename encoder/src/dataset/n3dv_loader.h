// Loader for N3DV (Neural 3D Video) scene directories:
//   poses_bounds.npy  one row of 17 per camera: 3x5 [R | centre | (H, W, f)] camera-to-world
//                     with LLFF axes (down, right, back), then near and far bounds;
//   the frames, the first of these layouts that is present:
//     camXX/images/*.png|jpg   frames extracted per camera,
//     frames/camXX/*.png|jpg   the same under frames/,
//     camXX.mp4                the original videos, decoded on demand;
//   sparse/0/                  optional COLMAP model whose points3D (e.g. COLMAP run on
//                              frame 0 with these poses) gives the initial points.
// Cameras are the cam* names in sorted order, matched to poses_bounds rows in that order.
// Frame f of a camera is its f-th image in natural name order (or video frame f); the
// capture has as many frames as the shortest camera. The principal point is the image
// centre and f is scaled by image width / W, as LLFF stores it.
#ifndef M4D_ENCODER_DATASET_N3DV_LOADER_H_
#define M4D_ENCODER_DATASET_N3DV_LOADER_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/capture_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

Status LoadN3dv(const std::string& dir, const CaptureOptions& options, Capture* capture);

// The camera of one poses_bounds row (17 values) for an image of width x height.
Status N3dvCamera(const double* row, int width, int height, Camera* camera);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_N3DV_LOADER_H_
