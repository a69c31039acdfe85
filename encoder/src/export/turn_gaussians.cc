#include "encoder/src/export/turn_gaussians.h"

#include <cmath>

#include "encoder/src/export/sh_rotation.h"

namespace m4d {

void RotationQuaternion(const AxisRotation& r, float q[4]) {
  const float* m = r.m;
  const double trace = double{m[0]} + m[4] + m[8];
  double w, x, y, z;
  // Shepperd: divide by the largest of the four candidates.
  if (trace > 0) {
    const double s = 2.0 * std::sqrt(1.0 + trace);
    w = 0.25 * s, x = (m[7] - m[5]) / s, y = (m[2] - m[6]) / s, z = (m[3] - m[1]) / s;
  } else if (m[0] >= m[4] && m[0] >= m[8]) {
    const double s = 2.0 * std::sqrt(1.0 + m[0] - m[4] - m[8]);
    w = (m[7] - m[5]) / s, x = 0.25 * s, y = (m[1] + m[3]) / s, z = (m[2] + m[6]) / s;
  } else if (m[4] >= m[8]) {
    const double s = 2.0 * std::sqrt(1.0 + m[4] - m[0] - m[8]);
    w = (m[2] - m[6]) / s, x = (m[1] + m[3]) / s, y = 0.25 * s, z = (m[5] + m[7]) / s;
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m[8] - m[0] - m[4]);
    w = (m[3] - m[1]) / s, x = (m[2] + m[6]) / s, y = (m[5] + m[7]) / s, z = 0.25 * s;
  }
  q[0] = static_cast<float>(w), q[1] = static_cast<float>(x);
  q[2] = static_cast<float>(y), q[3] = static_cast<float>(z);
}

void TurnGaussians(const AxisRotation& r, GaussianSet* set) {
  if (r.is_identity()) return;
  float a[4];
  RotationQuaternion(r, a);
  const ShRotation sh_rotation(r.m);
  const size_t stride = static_cast<size_t>(set->sh_floats());
  for (size_t i = 0; i < set->size(); ++i) {
    float* p = &set->positions[3 * i];
    const float x = p[0], y = p[1], z = p[2];
    for (int k = 0; k < 3; ++k) p[k] = r.m[3 * k] * x + r.m[3 * k + 1] * y + r.m[3 * k + 2] * z;
    float* q = &set->rotations[4 * i];  // a * q: first the Gaussian's turn, then the world's
    const float b[4] = {q[0], q[1], q[2], q[3]};
    q[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    q[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    q[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    q[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    if (set->sh_degree > 0) sh_rotation.Apply(set->sh_degree, &set->sh[i * stride]);
  }
}

}  // namespace m4d
