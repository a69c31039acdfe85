// Spherical-harmonics colour of a Gaussian, with the constants, basis signs and coefficient
// order of the reference 3DGS rasterizer: degree 0..3, coefficient k of channel c stored at
// sh[3 * k + c], evaluated in the unit direction from the camera centre to the Gaussian mean.
#ifndef M4D_RENDER_SH_EVALUATION_H_
#define M4D_RENDER_SH_EVALUATION_H_

namespace m4d {

constexpr int kMaxShDegree = 3;
constexpr int kMaxShCoefficients = 16;

constexpr float kShC0 = 0.28209479177387814f;
constexpr float kShC1 = 0.4886025119029199f;
constexpr float kShC2[5] = {1.0925484305920792f, -1.0925484305920792f, 0.31539156525252005f,
                            -1.0925484305920792f, 0.5462742152960396f};
constexpr float kShC3[7] = {-0.5900435899266435f, 2.890611442640554f,   -0.4570457994644658f,
                            0.3731763325901154f,  -0.4570457994644658f, 1.445305721320277f,
                            -0.5900435899266435f};

// The (degree + 1)^2 basis values at the unit direction (x, y, z).
template <typename T>
void ShBasis(int degree, T x, T y, T z, T* basis) {
  basis[0] = T(kShC0);
  if (degree < 1) return;
  basis[1] = -T(kShC1) * y;
  basis[2] = T(kShC1) * z;
  basis[3] = -T(kShC1) * x;
  if (degree < 2) return;
  const T xx = x * x, yy = y * y, zz = z * z;
  const T xy = x * y, yz = y * z, xz = x * z;
  basis[4] = T(kShC2[0]) * xy;
  basis[5] = T(kShC2[1]) * yz;
  basis[6] = T(kShC2[2]) * (T(2) * zz - xx - yy);
  basis[7] = T(kShC2[3]) * xz;
  basis[8] = T(kShC2[4]) * (xx - yy);
  if (degree < 3) return;
  basis[9] = T(kShC3[0]) * y * (T(3) * xx - yy);
  basis[10] = T(kShC3[1]) * xy * z;
  basis[11] = T(kShC3[2]) * y * (T(4) * zz - xx - yy);
  basis[12] = T(kShC3[3]) * z * (T(2) * zz - T(3) * xx - T(3) * yy);
  basis[13] = T(kShC3[4]) * x * (T(4) * zz - xx - yy);
  basis[14] = T(kShC3[5]) * z * (xx - yy);
  basis[15] = T(kShC3[6]) * x * (xx - T(3) * yy);
}

// Colour before clamping: sum_k basis[k] * sh[3k + c] + 0.5, over the first `coefficients`.
template <typename T, typename S>
void ShColour(const T* basis, int coefficients, const S* sh, T colour[3]) {
  for (int c = 0; c < 3; ++c) colour[c] = T(0);
  for (int k = 0; k < coefficients; ++k) {
    for (int c = 0; c < 3; ++c) colour[c] += basis[k] * T(sh[3 * k + c]);
  }
  for (int c = 0; c < 3; ++c) colour[c] += T(0.5);
}

}  // namespace m4d

#endif  // M4D_RENDER_SH_EVALUATION_H_
