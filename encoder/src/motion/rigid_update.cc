#include "encoder/src/motion/rigid_update.h"

#include <cmath>

namespace m4d {
namespace {

// r = d (x) q, quaternions (w, x, y, z).
void Compose(const float d[4], const float q[4], float r[4]) {
  r[0] = d[0] * q[0] - d[1] * q[1] - d[2] * q[2] - d[3] * q[3];
  r[1] = d[0] * q[1] + d[1] * q[0] + d[2] * q[3] - d[3] * q[2];
  r[2] = d[0] * q[2] - d[1] * q[3] + d[2] * q[0] + d[3] * q[1];
  r[3] = d[0] * q[3] + d[1] * q[2] - d[2] * q[1] + d[3] * q[0];
}

void Increment(const float o[7], float d[4]) {
  d[0] = 1.0f + o[3];
  d[1] = o[4];
  d[2] = o[5];
  d[3] = o[6];
}

constexpr float kMinNorm2 = 1e-30f;  // spec 6.3 step 6: below it the rotation resets

}  // namespace

void RigidUpdate(const float o[7], const float p[3], const float q[4], float p_out[3],
                 float q_out[4]) {
  for (int a = 0; a < 3; ++a) p_out[a] = p[a] + o[a];
  float d[4], r[4];
  Increment(o, d);
  Compose(d, q, r);
  float n2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3];
  if (!(n2 > kMinNorm2) || !std::isfinite(n2)) {
    q_out[0] = 1.0f;
    q_out[1] = q_out[2] = q_out[3] = 0.0f;
    return;
  }
  float inv = 1.0f / std::sqrt(n2);
  for (int m = 0; m < 4; ++m) q_out[m] = r[m] * inv;
}

void RigidUpdateBackward(const float o[7], const float q[4], const float dp_out[3],
                         const float dq_out[4], float d_o[7]) {
  for (int a = 0; a < 3; ++a) d_o[a] = dp_out[a];
  float d[4], r[4];
  Increment(o, d);
  Compose(d, q, r);
  float n2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3];
  if (!(n2 > kMinNorm2) || !std::isfinite(n2)) {
    d_o[3] = d_o[4] = d_o[5] = d_o[6] = 0.0f;
    return;
  }
  // Normalisation: dL/dr = (g - q_out (q_out . g)) / |r|.
  float inv = 1.0f / std::sqrt(n2);
  float dot = 0.0f;
  for (int m = 0; m < 4; ++m) dot += r[m] * inv * dq_out[m];
  float dr[4];
  for (int m = 0; m < 4; ++m) dr[m] = (dq_out[m] - r[m] * inv * dot) * inv;
  // r = d (x) q is linear in d; columns of dr/dd.
  d_o[3] = dr[0] * q[0] + dr[1] * q[1] + dr[2] * q[2] + dr[3] * q[3];
  d_o[4] = -dr[0] * q[1] + dr[1] * q[0] - dr[2] * q[3] + dr[3] * q[2];
  d_o[5] = -dr[0] * q[2] + dr[1] * q[3] + dr[2] * q[0] - dr[3] * q[1];
  d_o[6] = -dr[0] * q[3] - dr[1] * q[2] + dr[2] * q[1] + dr[3] * q[0];
}

}  // namespace m4d
