// LensDistortion: the lens models calibration tools write (COLMAP, OpenCV, nerfstudio) as
// maps between undistorted and distorted normalised image coordinates (x, y) = (X/Z, Y/Z).
// Written here, not taken from OpenCV, whose Debian development packages pull in over a
// hundred packages (Qt, GDAL, a database client) for the three functions undistortion needs.
#ifndef M4D_ENCODER_DATASET_LENS_DISTORTION_H_
#define M4D_ENCODER_DATASET_LENS_DISTORTION_H_

#include <string>

#include "sdk/src/common/status.h"

namespace m4d {

enum class LensModel {
  kNone,        // pinhole
  kRadial,      // k1, k2, k3 (COLMAP SIMPLE_RADIAL and RADIAL use k1 and k1, k2)
  kOpenCv,      // k1, k2, k3 and tangential p1, p2
  kFullOpenCv,  // OpenCV's rational model: (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 ... k6)
  kFisheye,     // OpenCV fisheye (Kannala-Brandt): theta (1 + k1 theta^2 + ... + k4 theta^8)
};

struct LensDistortion {
  LensModel model = LensModel::kNone;
  double k[6] = {};  // k1..k6 in OpenCV's naming; those the model does not use stay 0
  double p1 = 0, p2 = 0;
};

// The COLMAP name of the model ("PINHOLE", "RADIAL", "OPENCV", "FULL_OPENCV",
// "OPENCV_FISHEYE").
const char* LensModelName(LensModel model);

// Whether any coefficient is nonzero (or not a number): else the camera is a pinhole.
bool HasDistortion(const LensDistortion& distortion);

// M4D_ERR_INVALID_ARG, naming `what`, for a non-finite coefficient.
Status CheckLensDistortion(const LensDistortion& distortion, const std::string& what);

// The distorted coordinates of undistorted (x, y), OpenCV's documented formulas.
void Distort(const LensDistortion& distortion, double x, double y, double* xd, double* yd);

// The undistorted coordinates of distorted (xd, yd) by Newton's method; false when it does
// not converge to a point where the distortion is locally one-to-one (too strong a lens, or a
// point beyond the field of view the calibration describes).
bool Undistort(const LensDistortion& distortion, double xd, double yd, double* x, double* y);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_LENS_DISTORTION_H_
