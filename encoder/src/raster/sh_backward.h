// Gradient of the SH colour (sdk/src/render/sh_evaluation.h) with respect to the direction:
// the partial derivatives of each basis function in x, y and z.
#ifndef M4D_ENCODER_RASTER_SH_BACKWARD_H_
#define M4D_ENCODER_RASTER_SH_BACKWARD_H_

#include "sdk/src/render/sh_evaluation.h"

namespace m4d {

// grad[k] = d basis[k] / d(x, y, z) at the unit direction (x, y, z), for k below
// (degree + 1)^2. The direction is treated as unconstrained here; the caller projects out
// the radial part for the normalisation.
template <typename T>
void ShBasisGradient(int degree, T x, T y, T z, T grad[][3]) {
  for (int a = 0; a < 3; ++a) grad[0][a] = T(0);
  if (degree < 1) return;
  const T c1 = T(kShC1);
  const T g1[3][3] = {{0, -c1, 0}, {0, 0, c1}, {-c1, 0, 0}};
  for (int k = 0; k < 3; ++k) {
    for (int a = 0; a < 3; ++a) grad[1 + k][a] = g1[k][a];
  }
  if (degree < 2) return;
  const T xx = x * x, yy = y * y, zz = z * z;
  T c2[5];
  for (int k = 0; k < 5; ++k) c2[k] = T(kShC2[k]);
  const T g2[5][3] = {{c2[0] * y, c2[0] * x, 0},
                      {0, c2[1] * z, c2[1] * y},
                      {-T(2) * c2[2] * x, -T(2) * c2[2] * y, T(4) * c2[2] * z},
                      {c2[3] * z, 0, c2[3] * x},
                      {T(2) * c2[4] * x, -T(2) * c2[4] * y, 0}};
  for (int k = 0; k < 5; ++k) {
    for (int a = 0; a < 3; ++a) grad[4 + k][a] = g2[k][a];
  }
  if (degree < 3) return;
  T c3[7];
  for (int k = 0; k < 7; ++k) c3[k] = T(kShC3[k]);
  const T g3[7][3] = {
      {T(6) * c3[0] * x * y, c3[0] * (T(3) * xx - T(3) * yy), 0},
      {c3[1] * y * z, c3[1] * x * z, c3[1] * x * y},
      {-T(2) * c3[2] * x * y, c3[2] * (T(4) * zz - xx - T(3) * yy), T(8) * c3[2] * y * z},
      {-T(6) * c3[3] * x * z, -T(6) * c3[3] * y * z, c3[3] * (T(6) * zz - T(3) * xx - T(3) * yy)},
      {c3[4] * (T(4) * zz - T(3) * xx - yy), -T(2) * c3[4] * x * y, T(8) * c3[4] * x * z},
      {T(2) * c3[5] * x * z, -T(2) * c3[5] * y * z, c3[5] * (xx - yy)},
      {c3[6] * (T(3) * xx - T(3) * yy), -T(6) * c3[6] * x * y, 0}};
  for (int k = 0; k < 7; ++k) {
    for (int a = 0; a < 3; ++a) grad[9 + k][a] = g3[k][a];
  }
}

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_SH_BACKWARD_H_
