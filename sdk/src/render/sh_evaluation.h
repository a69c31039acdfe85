// Spherical-harmonics colour of a Gaussian, with the constants, basis signs and coefficient
// order of the reference 3DGS rasterizer: degree 0..3, coefficient k of channel c stored at
// sh[3 * k + c], evaluated in the unit direction from the camera centre to the Gaussian mean.
#ifndef M4D_SDK_RENDER_SH_EVALUATION_H_
#define M4D_SDK_RENDER_SH_EVALUATION_H_

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
void ShBasis(int degree, float x, float y, float z, float* basis);

// Colour before clamping: sum_k basis[k] * sh[3k + c] + 0.5 over the first `coefficients`.
void ShColour(const float* basis, int coefficients, const float* sh, float colour[3]);

}  // namespace m4d

#endif  // M4D_SDK_RENDER_SH_EVALUATION_H_
