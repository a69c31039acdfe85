// Undistortion of a camera with lens distortion to a pinhole camera of the same image size,
// as COLMAP's image_undistorter and OpenSplat do: the pinhole camera keeps only valid pixels
// (OpenCV's getOptimalNewCameraMatrix with alpha 0), and a remap table gives every pinhole
// pixel its source position, sampled bilinearly.
#ifndef M4D_ENCODER_DATASET_UNDISTORTION_H_
#define M4D_ENCODER_DATASET_UNDISTORTION_H_

#include <string>
#include <vector>

#include "encoder/src/dataset/lens_distortion.h"
#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

// The pinhole camera (pose and size of `distorted`) whose every pixel centre maps inside the
// distorted image, with the largest such field of view: the inner rectangle of the
// undistorted image border, found from every border pixel. Without distortion it is
// `distorted` itself. Errors name `what`: M4D_ERR_INVALID_ARG for non-finite coefficients
// or bad intrinsics, M4D_ERR_UNSUPPORTED for a distortion too strong to invert at the
// border or leaving no valid rectangle.
Status UndistortedCamera(const Camera& distorted, const LensDistortion& distortion,
                         const std::string& what, Camera* pinhole);

struct UndistortionMap {
  int width = 0, height = 0;                // the pinhole image
  int source_width = 0, source_height = 0;  // the distorted image
  // Per pinhole pixel, row-major: the distorted image's column and row there, in pixel
  // indices (pixel centres at integers), within the distorted image.
  std::vector<float> source;
};

// The remap table from `distorted` to `pinhole` (from UndistortedCamera);
// M4D_ERR_UNSUPPORTED naming `what` when a pixel maps outside the distorted image.
Status BuildUndistortionMap(const Camera& distorted, const LensDistortion& distortion,
                            const Camera& pinhole, const std::string& what, UndistortionMap* map);

// *out = source sampled bilinearly at the map's positions (any channel count).
Status Remap(const UndistortionMap& map, const Image& source, Image* out);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_UNDISTORTION_H_
