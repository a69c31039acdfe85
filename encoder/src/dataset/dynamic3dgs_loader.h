// Loader for the Dynamic 3D Gaussians layout (CMU Panoptic sequences as its authors
// prepared them):
//   train_meta.json  w, h; per frame and camera: k (3x3 intrinsics), w2c (4x4 world-to-camera,
//                    OpenCV axes), fn (image file relative to ims/), cam_id;
//   ims/<fn>         the images;
//   init_pt_cld.npz  optional initial points, array "data" of N x 7 (x y z, r g b in [0, 1],
//                    segmentation label, ignored).
// Cameras are ordered by cam_id and named by it; every frame must list every camera once.
#ifndef M4D_ENCODER_DATASET_DYNAMIC3DGS_LOADER_H_
#define M4D_ENCODER_DATASET_DYNAMIC3DGS_LOADER_H_

#include <string>

#include "encoder/src/capture/capture.h"
#include "encoder/src/dataset/capture_options.h"
#include "sdk/src/common/status.h"

namespace m4d {

Status LoadDynamic3dgs(const std::string& dir, const CaptureOptions& options, Capture* capture);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_DYNAMIC3DGS_LOADER_H_
