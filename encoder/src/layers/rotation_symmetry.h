// The canonical form of a Gaussian's rotation under the symmetries of its axes.
//
// A Gaussian's covariance R S^2 R^T is unchanged when R becomes R G and its three scales are
// permuted as G permutes the axes, for each G of the 24 rotations that map the coordinate axes
// onto themselves. Of these equivalent rotations, the one nearest the identity (the quaternion
// with the largest |w|) has |x|, |y|, |z| at most sin(pi / 8) = 0.383, where the three smallest
// components of any unit quaternion span +-1 / sqrt(2): smallest-three rotations (spec 5.4)
// then need one bit less per component for the same step.
#ifndef M4D_ENCODER_LAYERS_ROTATION_SYMMETRY_H_
#define M4D_ENCODER_LAYERS_ROTATION_SYMMETRY_H_

#include <cstdint>
#include <vector>

#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// sin(pi / 8): the largest |x|, |y| or |z| of a canonical rotation.
constexpr float kCanonicalRotationBound = 0.38268343f;

// Replaces each Gaussian's rotation by the equivalent one nearest the identity, with w >= 0,
// and permutes its log scales to match: the covariances stay those of before, up to f32
// rounding. A zero or non-finite quaternion is left as it is. `applied`, when not null,
// receives the symmetry applied to each Gaussian (for RestoreRotationAxes). The rotation and
// log-scale arrays must hold 4 and 3 values per Gaussian.
void CanonicalizeRotations(GaussianSet* set, std::vector<uint8_t>* applied);

// Undoes CanonicalizeRotations on a set whose values may have changed since (a quantized copy):
// each Gaussian's rotation and scales go back to its former axes, and the quaternion to the
// sign of its `original` (4 floats per Gaussian), so that it stays the same parameter.
void RestoreRotationAxes(const std::vector<uint8_t>& applied, const float* original,
                         GaussianSet* set);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_ROTATION_SYMMETRY_H_
