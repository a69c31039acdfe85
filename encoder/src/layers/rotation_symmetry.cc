#include "encoder/src/layers/rotation_symmetry.h"

#include <array>
#include <cmath>

namespace m4d {
namespace {

// One of the 24 rotations: its quaternion (w, x, y, z) and, for each axis j of R G, the axis of
// R it is (up to sign), whose scale it takes.
struct AxisSymmetry {
  std::array<double, 4> q;
  std::array<int, 3> axis;
};

using Quaternion = std::array<double, 4>;

Quaternion Multiply(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// Column j of the rotation matrix of g is +-e_k: axis j of R G is axis k of R.
AxisSymmetry WithAxes(const Quaternion& g) {
  const Quaternion unit_axes[3] = {{0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  const Quaternion conjugate = {g[0], -g[1], -g[2], -g[3]};
  AxisSymmetry s{g, {0, 1, 2}};
  for (int j = 0; j < 3; ++j) {
    const Quaternion image = Multiply(Multiply(g, unit_axes[j]), conjugate);  // g e_j g*
    for (int k = 0; k < 3; ++k) {
      if (std::fabs(image[k + 1]) > 0.5) s.axis[j] = k;
    }
  }
  return s;
}

// The identity first: of equally near rotations, the first in this order is kept.
std::array<AxisSymmetry, 24> MakeSymmetries() {
  const double h = std::sqrt(0.5);
  std::array<AxisSymmetry, 24> table;
  size_t n = 0;
  table[n++] = WithAxes({1, 0, 0, 0});
  for (int a = 1; a <= 3; ++a) {  // a quarter turn about an axis, either way
    for (double sign : {1.0, -1.0}) {
      Quaternion g = {h, 0, 0, 0};
      g[a] = sign * h;
      table[n++] = WithAxes(g);
    }
  }
  for (int a = 1; a <= 3; ++a) {  // a half turn about an axis
    Quaternion g = {0, 0, 0, 0};
    g[a] = 1;
    table[n++] = WithAxes(g);
  }
  for (int a = 1; a <= 3; ++a) {  // a half turn about the diagonal of two axes
    for (int b = a + 1; b <= 3; ++b) {
      for (double sign : {1.0, -1.0}) {
        Quaternion g = {0, 0, 0, 0};
        g[a] = h;
        g[b] = sign * h;
        table[n++] = WithAxes(g);
      }
    }
  }
  for (double x : {0.5, -0.5}) {  // a third of a turn about a diagonal of the cube
    for (double y : {0.5, -0.5}) {
      for (double z : {0.5, -0.5}) table[n++] = WithAxes({0.5, x, y, z});
    }
  }
  return table;
}

const std::array<AxisSymmetry, 24>& Symmetries() {
  static const std::array<AxisSymmetry, 24> table = MakeSymmetries();
  return table;
}

// The symmetry that brings the unit quaternion q nearest the identity.
int NearestToIdentity(const Quaternion& q) {
  const std::array<AxisSymmetry, 24>& table = Symmetries();
  int best = 0;
  double best_w = -1.0;
  for (int k = 0; k < 24; ++k) {
    const double w = std::fabs(Multiply(q, table[static_cast<size_t>(k)].q)[0]);
    if (w > best_w) {
      best_w = w;
      best = k;
    }
  }
  return best;
}

void Apply(const Quaternion& q, const AxisSymmetry& s, float* rotation, float* log_scales) {
  Quaternion r = Multiply(q, s.q);
  const double sign = r[0] < 0.0 ? -1.0 : 1.0;
  for (int c = 0; c < 4; ++c) rotation[c] = static_cast<float>(sign * r[static_cast<size_t>(c)]);
  const float before[3] = {log_scales[0], log_scales[1], log_scales[2]};
  for (int j = 0; j < 3; ++j) log_scales[j] = before[s.axis[static_cast<size_t>(j)]];
}

}  // namespace

void CanonicalizeRotations(GaussianSet* set, std::vector<uint8_t>* applied) {
  const size_t n = set->size();
  if (applied != nullptr) applied->assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    float* rotation = &set->rotations[4 * i];
    Quaternion q;
    double norm = 0.0;
    for (size_t c = 0; c < 4; ++c) {
      q[c] = rotation[c];
      norm += q[c] * q[c];
    }
    norm = std::sqrt(norm);
    if (!(norm > 0.0) || !std::isfinite(norm)) continue;
    for (double& c : q) c /= norm;
    const int k = NearestToIdentity(q);
    Apply(q, Symmetries()[static_cast<size_t>(k)], rotation, &set->log_scales[3 * i]);
    if (applied != nullptr) (*applied)[i] = static_cast<uint8_t>(k);
  }
}

void RestoreRotationAxes(const std::vector<uint8_t>& applied, const float* original,
                         GaussianSet* set) {
  for (size_t i = 0; i < applied.size(); ++i) {
    const AxisSymmetry& s = Symmetries()[applied[i]];
    float* rotation = &set->rotations[4 * i];
    const Quaternion g_inverse = {s.q[0], -s.q[1], -s.q[2], -s.q[3]};
    const Quaternion r = Multiply({rotation[0], rotation[1], rotation[2], rotation[3]}, g_inverse);
    double dot = 0.0;
    for (size_t c = 0; c < 4; ++c) dot += r[c] * original[4 * i + c];
    const double sign = dot < 0.0 ? -1.0 : 1.0;
    for (size_t c = 0; c < 4; ++c) rotation[c] = static_cast<float>(sign * r[c]);
    float* log_scales = &set->log_scales[3 * i];
    const float canonical[3] = {log_scales[0], log_scales[1], log_scales[2]};
    for (int j = 0; j < 3; ++j) log_scales[s.axis[static_cast<size_t>(j)]] = canonical[j];
  }
}

}  // namespace m4d
