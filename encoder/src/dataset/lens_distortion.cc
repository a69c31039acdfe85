#include "encoder/src/dataset/lens_distortion.h"

#include <algorithm>
#include <cmath>

namespace m4d {
namespace {

constexpr int kMaxIterations = 100;
constexpr double kTolerance = 1e-12;  // on the distorted coordinates, relative to 1 + |xd|
constexpr double kHalfPi = 1.5707963267948966;

void DistortRational(const LensDistortion& d, double x, double y, double* xd, double* yd) {
  const double x2 = x * x, y2 = y * y, xy = x * y, r2 = x2 + y2;
  const double* k = d.k;
  const double radial =
      (1 + r2 * (k[0] + r2 * (k[1] + r2 * k[2]))) / (1 + r2 * (k[3] + r2 * (k[4] + r2 * k[5])));
  *xd = x * radial + 2 * d.p1 * xy + d.p2 * (r2 + 2 * x2);
  *yd = y * radial + d.p1 * (r2 + 2 * y2) + 2 * d.p2 * xy;
}

void DistortFisheye(const LensDistortion& d, double x, double y, double* xd, double* yd) {
  const double r = std::hypot(x, y);
  const double theta = std::atan(r), t2 = theta * theta;
  const double* k = d.k;
  const double theta_d = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
  const double scale = r > 0 ? theta_d / r : 1;
  *xd = x * scale;
  *yd = y * scale;
}

// d(xd, yd) / d(x, y) row-major, by central differences.
void Jacobian(const LensDistortion& d, double x, double y, double j[4]) {
  const double h = 1e-7 * (1 + std::fabs(x) + std::fabs(y));
  double a[2], b[2];
  DistortRational(d, x + h, y, &a[0], &a[1]);
  DistortRational(d, x - h, y, &b[0], &b[1]);
  j[0] = (a[0] - b[0]) / (2 * h);
  j[2] = (a[1] - b[1]) / (2 * h);
  DistortRational(d, x, y + h, &a[0], &a[1]);
  DistortRational(d, x, y - h, &b[0], &b[1]);
  j[1] = (a[0] - b[0]) / (2 * h);
  j[3] = (a[1] - b[1]) / (2 * h);
}

// Newton's method in 2D with a central-difference Jacobian (as COLMAP does), halving steps
// that do not reduce the residual.
bool UndistortRational(const LensDistortion& d, double xd, double yd, double* x, double* y) {
  const double tolerance = kTolerance * (1 + std::fabs(xd) + std::fabs(yd));
  double u = xd, v = yd, fu, fv;
  DistortRational(d, u, v, &fu, &fv);
  double residual = std::hypot(fu - xd, fv - yd);
  for (int i = 0; i < kMaxIterations; ++i) {
    double j[4];
    Jacobian(d, u, v, j);
    const double det = j[0] * j[3] - j[1] * j[2];
    // A negative determinant is a solution past the radius where the lens folds over.
    if (residual <= tolerance) {
      *x = u;
      *y = v;
      return det > 0;
    }
    if (!(std::fabs(det) > 1e-12)) return false;
    const double ru = fu - xd, rv = fv - yd;
    const double du = (j[3] * ru - j[1] * rv) / det, dv = (j[0] * rv - j[2] * ru) / det;
    double step = 1, nu, nv, next;
    for (int halving = 0;; ++halving, step *= 0.5) {
      nu = u - step * du;
      nv = v - step * dv;
      DistortRational(d, nu, nv, &fu, &fv);
      next = std::hypot(fu - xd, fv - yd);
      if (next < residual) break;
      if (halving == 30) return false;  // no descent: diverging, or not a number
    }
    u = nu;
    v = nv;
    residual = next;
  }
  return false;
}

// Newton's method on theta_d(theta) = |(xd, yd)|; the point must lie within 90 degrees of
// the axis for a pinhole camera to see it.
bool UndistortFisheye(const LensDistortion& d, double xd, double yd, double* x, double* y) {
  const double theta_d = std::hypot(xd, yd);
  const double* k = d.k;
  double theta = std::min(theta_d, 1.5);
  for (int i = 0; i < kMaxIterations; ++i) {
    const double t2 = theta * theta;
    const double g = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])))) - theta_d;
    const double slope = 1 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
    if (!(slope > 0)) return false;  // folded over, or not a number
    if (std::fabs(g) <= kTolerance * (1 + theta_d)) {
      if (!(theta < kHalfPi)) return false;
      const double scale = theta_d > 0 ? std::tan(theta) / theta_d : 1;
      *x = xd * scale;
      *y = yd * scale;
      return true;
    }
    theta = std::clamp(theta - g / slope, 0.0, kHalfPi);
  }
  return false;
}

}  // namespace

const char* LensModelName(LensModel model) {
  switch (model) {
    case LensModel::kNone:
      return "PINHOLE";
    case LensModel::kRadial:
      return "RADIAL";
    case LensModel::kOpenCv:
      return "OPENCV";
    case LensModel::kFullOpenCv:
      return "FULL_OPENCV";
    case LensModel::kFisheye:
      return "OPENCV_FISHEYE";
  }
  return "unknown";
}

bool HasDistortion(const LensDistortion& distortion) {
  bool distorted = distortion.p1 != 0 || distortion.p2 != 0;
  for (double k : distortion.k) distorted |= k != 0;
  return distorted;
}

Status CheckLensDistortion(const LensDistortion& distortion, const std::string& what) {
  bool finite = std::isfinite(distortion.p1) && std::isfinite(distortion.p2);
  for (double k : distortion.k) finite &= std::isfinite(k);
  if (finite) return Status::Ok();
  return Status(M4D_ERR_INVALID_ARG, what + ": lens distortion coefficients must be finite");
}

void Distort(const LensDistortion& distortion, double x, double y, double* xd, double* yd) {
  if (distortion.model == LensModel::kFisheye) {
    DistortFisheye(distortion, x, y, xd, yd);
  } else {
    DistortRational(distortion, x, y, xd, yd);
  }
}

bool Undistort(const LensDistortion& distortion, double xd, double yd, double* x, double* y) {
  return distortion.model == LensModel::kFisheye ? UndistortFisheye(distortion, xd, yd, x, y)
                                                 : UndistortRational(distortion, xd, yd, x, y);
}

}  // namespace m4d
