#include "sdk/src/render/sh_evaluation.h"

namespace m4d {

void ShBasis(int degree, float x, float y, float z, float* basis) {
  basis[0] = kShC0;
  if (degree < 1) return;
  basis[1] = -kShC1 * y;
  basis[2] = kShC1 * z;
  basis[3] = -kShC1 * x;
  if (degree < 2) return;
  const float xx = x * x, yy = y * y, zz = z * z;
  const float xy = x * y, yz = y * z, xz = x * z;
  basis[4] = kShC2[0] * xy;
  basis[5] = kShC2[1] * yz;
  basis[6] = kShC2[2] * (2.0f * zz - xx - yy);
  basis[7] = kShC2[3] * xz;
  basis[8] = kShC2[4] * (xx - yy);
  if (degree < 3) return;
  basis[9] = kShC3[0] * y * (3.0f * xx - yy);
  basis[10] = kShC3[1] * xy * z;
  basis[11] = kShC3[2] * y * (4.0f * zz - xx - yy);
  basis[12] = kShC3[3] * z * (2.0f * zz - 3.0f * xx - 3.0f * yy);
  basis[13] = kShC3[4] * x * (4.0f * zz - xx - yy);
  basis[14] = kShC3[5] * z * (xx - yy);
  basis[15] = kShC3[6] * x * (xx - 3.0f * yy);
}

void ShColour(const float* basis, int coefficients, const float* sh, float colour[3]) {
  float sum[3] = {0.0f, 0.0f, 0.0f};
  for (int k = 0; k < coefficients; ++k) {
    for (int c = 0; c < 3; ++c) sum[c] += basis[k] * sh[3 * k + c];
  }
  for (int c = 0; c < 3; ++c) colour[c] = sum[c] + 0.5f;
}

}  // namespace m4d
