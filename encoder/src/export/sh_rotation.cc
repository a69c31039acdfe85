#include "encoder/src/export/sh_rotation.h"

#include <cmath>

namespace m4d {
namespace {

constexpr int kSamples = 96;  // well above the 16 unknowns per column
constexpr int kN = kMaxShCoefficients;

// Directions spread over the sphere (a Fibonacci lattice).
void SampleDirection(int i, float d[3]) {
  const double golden = 2.399963229728653;  // pi * (3 - sqrt(5))
  const double z = 1.0 - (2.0 * i + 1.0) / kSamples;
  const double r = std::sqrt(1.0 - z * z);
  d[0] = static_cast<float>(r * std::cos(golden * i));
  d[1] = static_cast<float>(r * std::sin(golden * i));
  d[2] = static_cast<float>(z);
}

// Solves a x = b for each of the kN columns of b (Gauss-Jordan with partial pivoting); a is
// symmetric positive definite here (the normal equations of the fit).
void Solve(double a[kN][kN], double b[kN][kN]) {
  for (int col = 0; col < kN; ++col) {
    int pivot = col;
    for (int r = col + 1; r < kN; ++r) {
      if (std::fabs(a[r][col]) > std::fabs(a[pivot][col])) pivot = r;
    }
    for (int c = 0; c < kN; ++c)
      std::swap(a[col][c], a[pivot][c]), std::swap(b[col][c], b[pivot][c]);
    const double inv = 1.0 / a[col][col];
    for (int r = 0; r < kN; ++r) {
      if (r == col) continue;
      const double f = a[r][col] * inv;
      for (int c = 0; c < kN; ++c) a[r][c] -= f * a[col][c], b[r][c] -= f * b[col][c];
    }
  }
  for (int r = 0; r < kN; ++r) {
    for (int c = 0; c < kN; ++c) b[r][c] /= a[r][r];
  }
}

}  // namespace

ShRotation::ShRotation(const float r[9]) {
  // Fit c' with B c' = C c for every c: B[s][k] = Y_k(d_s), C[s][k] = Y_k(R^T d_s).
  double btb[kN][kN] = {}, btc[kN][kN] = {};
  for (int s = 0; s < kSamples; ++s) {
    float d[3], turned[3], y[kN], yt[kN];
    SampleDirection(s, d);
    for (int i = 0; i < 3; ++i) turned[i] = r[i] * d[0] + r[3 + i] * d[1] + r[6 + i] * d[2];
    ShBasis(kMaxShDegree, d[0], d[1], d[2], y);
    ShBasis(kMaxShDegree, turned[0], turned[1], turned[2], yt);
    for (int i = 0; i < kN; ++i) {
      for (int j = 0; j < kN; ++j)
        btb[i][j] += double{y[i]} * y[j], btc[i][j] += double{y[i]} * yt[j];
    }
  }
  Solve(btb, btc);
  for (int i = 0; i < kN; ++i) {
    for (int j = 0; j < kN; ++j) {
      // Bands do not mix; what float rounding leaves outside a band, or around the exact
      // 0 and +-1 of an axis permutation, is dropped.
      const int bi = static_cast<int>(std::sqrt(i + 0.5)),
                bj = static_cast<int>(std::sqrt(j + 0.5));
      const double v = bi == bj ? btc[i][j] : 0.0;
      m_[i][j] = std::fabs(v) < 1e-5                    ? 0.0
                 : std::fabs(std::fabs(v) - 1.0) < 1e-5 ? (v > 0 ? 1.0 : -1.0)
                                                        : v;
    }
  }
}

void ShRotation::Apply(int degree, float* sh) const {
  const int n = (degree + 1) * (degree + 1);
  double out[kN][3] = {};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int c = 0; c < 3; ++c) out[i][c] += m_[i][j] * sh[3 * j + c];
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) sh[3 * i + c] = static_cast<float>(out[i][c]);
  }
}

}  // namespace m4d
