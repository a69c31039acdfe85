// Lens distortion for the realistic synthetic scene (CaptureRealism k1, k2, p1, p2): a view
// is rendered as a pinhole image on a canvas wider than the view (same focal length, the
// principal point moved by the margins) so that every distorted pixel has content, then
// resampled: each pixel of the distorted view takes the canvas, bilinearly, at the
// undistorted position of its centre (Undistort of dataset/lens_distortion.h).
#ifndef M4D_ENCODER_SYNTHETIC_LENS_RESAMPLING_H_
#define M4D_ENCODER_SYNTHETIC_LENS_RESAMPLING_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "encoder/src/dataset/lens_distortion.h"
#include "encoder/src/dataset/undistortion.h"
#include "encoder/src/image/image.h"
#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

// The OpenCV model with the options' coefficients as written (ShortestDecimal);
// LensModel::kNone when all are 0.
LensDistortion SceneLensDistortion(const CaptureRealism& realism);

class LensResampler {
 public:
  // For views with the intrinsics of `camera` (the rig shares them) through `distortion`.
  // M4D_ERR_UNSUPPORTED when a pixel has no undistorted position (validated options have).
  static Status Create(const Camera& camera, const LensDistortion& distortion,
                       std::unique_ptr<LensResampler>* resampler);

  // `camera` (its pose) with the canvas's size and principal point, for rendering.
  Camera Canvas(const Camera& camera) const;

  // canvas_rgb: the canvas's 8-bit RGB. *levels: the distorted view's RGB samples in 8-bit
  // levels (0..255), unrounded.
  Status Distort(const std::vector<uint8_t>& canvas_rgb, std::vector<float>* levels);

 private:
  LensResampler() = default;

  int margin_x_ = 0, margin_y_ = 0;  // canvas pixels left of and above the view
  UndistortionMap map_;              // here: per view pixel, its position on the canvas
  Image canvas_, view_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_LENS_RESAMPLING_H_
