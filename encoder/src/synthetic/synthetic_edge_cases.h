// Synthetic content at the edges of the decoding process, for conformance streams.
#ifndef M4D_ENCODER_SYNTHETIC_SYNTHETIC_EDGE_CASES_H_
#define M4D_ENCODER_SYNTHETIC_SYNTHETIC_EDGE_CASES_H_

#include <cstdint>

#include "encoder/src/layers/motion_grid_writer.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

// Edge cases of the decoding process for conformance streams: content on which decoders that
// bend spec 5.4 or 6.3 in ways random content hides give other hashes. In the grid box,
// nominally [0, 2]^3, the dynamic Gaussians lie
// - where the motion levels are non-zero, with steps that are not powers of two (a decoder
//   that scales each corner before interpolating gets other floats), some exactly on the upper
//   faces of the box (the cell index clamp of 6.3 step 2 picks the corner they depend on);
// - where the MLP turns the rotation to d = 0 (n2 = 0), to a tiny d (n2 below 1e-30) or to an
//   overflowing d (n2 infinite): the identity of 6.3 step 6;
// - where the MLP output overflows to infinity: unchanged (6.3 step 4).
// Their opacities are -0 and their higher SH -0 and +0 in turn: constant groups (bits 0) whose
// -0 mins spec 5.4 decodes to +0.
GridConfig EdgeCaseGridConfig();
MlpConfig EdgeCaseMlpConfig();
GaussianSet EdgeCaseGaussianSet(size_t n, int sh_degree, uint64_t seed);
// The MLP of EdgeCaseMlpConfig() that gives each region its outputs.
MlpWeights EdgeCaseMlp();
// The grid of EdgeCaseGridConfig() for the current dynamic set: random motion values, and a
// box whose upper face on each axis passes exactly through the set's farthest Gaussian.
FloatMotionGrid EdgeCaseMotionGrid(uint64_t seed, const GaussianSet& dynamic_set);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SYNTHETIC_EDGE_CASES_H_
