#include "encoder/src/export/axis_rotation.h"

namespace m4d {
namespace {

constexpr int kNegY = 4;  // M4D_UP_NEG_Y
constexpr int kPosY = 3;  // M4D_UP_POS_Y

int AxisIndex(int code) { return (code - 1) / 2; }
float AxisSign(int code) { return code % 2 == 1 ? 1.0f : -1.0f; }

}  // namespace

bool AxisRotation::is_identity() const {
  for (int i = 0; i < 9; ++i) {
    if (m[i] != (i % 4 == 0 ? 1.0f : 0.0f)) return false;
  }
  return true;
}

void UpAxisVector(int up_axis, float v[3]) {
  v[0] = v[1] = v[2] = 0;
  if (up_axis >= 1 && up_axis <= 6) v[AxisIndex(up_axis)] = AxisSign(up_axis);
}

AxisRotation RotationBetweenAxes(int from, int to) {
  AxisRotation r;
  if (from == to) return r;
  float f[3], t[3];
  UpAxisVector(from, f);
  UpAxisVector(to, t);
  if (AxisIndex(from) == AxisIndex(to)) {  // 2 k k^T - I, k the next axis
    const int k = (AxisIndex(from) + 1) % 3;
    for (int i = 0; i < 9; ++i) r.m[i] = i == 4 * k ? 1.0f : i % 4 == 0 ? -1.0f : 0.0f;
    return r;
  }
  // The quarter turn about n = f x t: t f^T - f t^T + n n^T maps f to t, t to -f, n to n.
  const float n[3] = {f[1] * t[2] - f[2] * t[1], f[2] * t[0] - f[0] * t[2],
                      f[0] * t[1] - f[1] * t[0]};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r.m[3 * i + j] = t[i] * f[j] - f[i] * t[j] + n[i] * n[j];
  }
  return r;
}

AxisRotation PlyFrame(int up_axis) {
  return up_axis >= 1 && up_axis <= 6 ? RotationBetweenAxes(up_axis, kNegY) : AxisRotation();
}

AxisRotation GltfFrame(int up_axis) {
  return Compose(RotationBetweenAxes(kNegY, kPosY), PlyFrame(up_axis));
}

AxisRotation Compose(const AxisRotation& r, const AxisRotation& s) {
  AxisRotation out;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      float v = 0;
      for (int k = 0; k < 3; ++k) v += r.m[3 * i + k] * s.m[3 * k + j];
      out.m[3 * i + j] = v;
    }
  }
  return out;
}

}  // namespace m4d
