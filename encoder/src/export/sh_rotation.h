// Spherical-harmonics colour of a rotated world. A Gaussian whose world turns by R (world' =
// R world) must show the same colour from the turned directions: f'(d) = f(R^T d). Each SH
// band mixes only within itself, so the new coefficients are a block-diagonal linear map of
// the old, fitted once per rotation by least squares over sample directions of the renderer's
// own basis (render/sh_evaluation.h), exact up to float rounding for any rotation.
#ifndef M4D_ENCODER_EXPORT_SH_ROTATION_H_
#define M4D_ENCODER_EXPORT_SH_ROTATION_H_

#include "sdk/src/render/sh_evaluation.h"

namespace m4d {

class ShRotation {
 public:
  // r: row-major 3x3 rotation.
  explicit ShRotation(const float r[9]);
  // Turns one Gaussian's coefficients in place: sh[3 * k + c] for k < (degree + 1)^2.
  void Apply(int degree, float* sh) const;
  // Coefficient k' of the rotated function per unit of coefficient k.
  double weight(int to, int from) const { return m_[to][from]; }

 private:
  double m_[kMaxShCoefficients][kMaxShCoefficients] = {};
};

}  // namespace m4d

#endif  // M4D_ENCODER_EXPORT_SH_ROTATION_H_
