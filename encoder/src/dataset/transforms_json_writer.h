// Writing a fixed-rig multi-view capture's transforms.json (nerfstudio's layout with the
// "camera" and "time_index" extensions; the layout is described in
// encoder/src/synthetic/README.md).
#ifndef M4D_ENCODER_DATASET_TRANSFORMS_JSON_WRITER_H_
#define M4D_ENCODER_DATASET_TRANSFORMS_JSON_WRITER_H_

#include <functional>
#include <string>
#include <vector>

#include "encoder/src/dataset/lens_distortion.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

struct TransformsJsonRig {
  std::vector<Camera> cameras;            // the same every frame
  std::vector<std::string> camera_names;  // one per camera
  int frame_count = 0;
  // The image of (frame, camera), relative to the transforms.json directory.
  std::function<std::string(int frame, int camera)> image_path;
  std::string ply_file_path;  // empty: no "ply_file_path"
  // Writes the world mirrored through x = 0 (x negated in every transform_matrix: rotations
  // of determinant -1), as some calibration tools' left-handed output is.
  bool mirror_world_x = false;
  // The lens every camera shares: none, or the OPENCV model's k1, k2, k3, p1, p2 (written
  // beside the shared intrinsics; k3 only when nonzero).
  LensDistortion distortion;
};

// The JSON text: shared intrinsics from camera 0 (entries whose camera differs carry their
// own), one entry per (frame, camera) in frame-major order with camera-to-world matrices in
// OpenGL axes. M4D_ERR_INVALID_ARG for an empty rig, mismatched names, an invalid camera or
// a lens model other than OPENCV.
Status TransformsJsonText(const TransformsJsonRig& rig, std::string* text);

Status WriteTransformsJson(const std::string& path, const TransformsJsonRig& rig);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_TRANSFORMS_JSON_WRITER_H_
