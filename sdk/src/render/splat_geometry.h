// Per-Gaussian geometry of the reference 3DGS model, shared by preprocessing and its
// gradient: rotation from a unit quaternion, the 3D covariance R S S^T R^T, and the EWA
// Jacobian of the pinhole projection with the reference's clamping of X/Z and Y/Z.
#ifndef M4D_RENDER_SPLAT_GEOMETRY_H_
#define M4D_RENDER_SPLAT_GEOMETRY_H_

namespace m4d {

// Row-major rotation matrix of the unit quaternion q = (w, x, y, z).
template <typename T>
void QuaternionToRotation(const T q[4], T r[9]) {
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  r[0] = T(1) - T(2) * (y * y + z * z);
  r[1] = T(2) * (x * y - w * z);
  r[2] = T(2) * (x * z + w * y);
  r[3] = T(2) * (x * y + w * z);
  r[4] = T(1) - T(2) * (x * x + z * z);
  r[5] = T(2) * (y * z - w * x);
  r[6] = T(2) * (x * z - w * y);
  r[7] = T(2) * (y * z + w * x);
  r[8] = T(1) - T(2) * (x * x + y * y);
}

// Symmetric 3x3 covariance M M^T with M = R diag(scale), as a full row-major matrix.
template <typename T>
void Covariance3D(const T r[9], const T scale[3], T cov[9]) {
  T m[9];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[3 * i + j] = r[3 * i + j] * scale[j];
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      cov[3 * i + j] =
          m[3 * i] * m[3 * j] + m[3 * i + 1] * m[3 * j + 1] + m[3 * i + 2] * m[3 * j + 2];
    }
  }
}

template <typename T>
T ClampTo(T v, T lo, T hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// The 2x3 matrix J W of the EWA projection (J: Jacobian of the pinhole projection at the
// camera-space point t, with t.x / t.z and t.y / t.z clamped to the given limits; W: the
// camera rotation, row-major). Row 0 maps to u, row 1 to v.
template <typename T>
void ProjectionJacobian(const T t[3], T fx, T fy, const T limit_x[2], const T limit_y[2],
                        const T w[9], T jw[6]) {
  const T inv_z = T(1) / t[2];
  const T xz = ClampTo(t[0] * inv_z, limit_x[0], limit_x[1]);
  const T yz = ClampTo(t[1] * inv_z, limit_y[0], limit_y[1]);
  const T j00 = fx * inv_z, j02 = -fx * xz * inv_z;
  const T j11 = fy * inv_z, j12 = -fy * yz * inv_z;
  for (int k = 0; k < 3; ++k) {
    jw[k] = j00 * w[k] + j02 * w[6 + k];
    jw[3 + k] = j11 * w[3 + k] + j12 * w[6 + k];
  }
}

// The 2D covariance (a, b, c) = J W cov3 (J W)^T before dilation.
template <typename T>
void ProjectCovariance(const T jw[6], const T cov3[9], T* a, T* b, T* c) {
  T m[6];  // J W cov3
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k < 3; ++k) {
      m[3 * i + k] =
          jw[3 * i] * cov3[k] + jw[3 * i + 1] * cov3[3 + k] + jw[3 * i + 2] * cov3[6 + k];
    }
  }
  *a = m[0] * jw[0] + m[1] * jw[1] + m[2] * jw[2];
  *b = m[0] * jw[3] + m[1] * jw[4] + m[2] * jw[5];
  *c = m[3] * jw[3] + m[4] * jw[4] + m[5] * jw[5];
}

}  // namespace m4d

#endif  // M4D_RENDER_SPLAT_GEOMETRY_H_
