#include "encoder/src/compensation/compensation_candidates.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/train/training_random.h"

namespace m4d {
namespace {

void CopyGaussian(const GaussianSet& from, size_t i, GaussianSet* to) {
  const size_t j = to->size();
  to->Resize(j + 1);
  std::copy_n(&from.positions[3 * i], 3, &to->positions[3 * j]);
  std::copy_n(&from.log_scales[3 * i], 3, &to->log_scales[3 * j]);
  std::copy_n(&from.rotations[4 * i], 4, &to->rotations[4 * j]);
  to->opacity_logits[j] = from.opacity_logits[i];
  const size_t k = static_cast<size_t>(from.sh_floats());
  std::copy_n(&from.sh[k * i], k, &to->sh[k * j]);
}

// Rotation matrix of the unnormalised quaternion (w, x, y, z).
void RotationMatrix(const float* q, float r[9]) {
  float n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  float w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y - w * z), r[2] = 2 * (x * z + w * y);
  r[3] = 2 * (x * y + w * z), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z - w * x);
  r[6] = 2 * (x * z - w * y), r[7] = 2 * (y * z + w * x), r[8] = 1 - 2 * (x * x + y * y);
}

// Appends two children of Gaussian i: centres from N(mu, 2 Sigma), scales / divisor.
void Split(const GaussianSet& moved, size_t i, float divisor, TrainingRandom* rng,
           GaussianSet* added) {
  float r[9];
  RotationMatrix(&moved.rotations[4 * i], r);
  for (int child = 0; child < 2; ++child) {
    CopyGaussian(moved, i, added);
    const size_t j = added->size() - 1;
    float local[3];
    for (int a = 0; a < 3; ++a) {
      local[a] = std::sqrt(2.0f) * std::exp(moved.log_scales[3 * i + a]) * rng->Normal();
    }
    for (int a = 0; a < 3; ++a) {
      added->positions[3 * j + a] +=
          r[3 * a] * local[0] + r[3 * a + 1] * local[1] + r[3 * a + 2] * local[2];
      added->log_scales[3 * j + a] -= std::log(divisor);
    }
  }
}

}  // namespace

float IncrementAngle(const float* o) {
  float w = 1.0f + o[3];
  float v = std::sqrt(o[4] * o[4] + o[5] * o[5] + o[6] * o[6]);
  return 2.0f * std::atan2(v, std::fabs(w));
}

CompensationCandidates ProposeCompensation(const GaussianSet& moved,
                                           const std::vector<float>& viewspace_gradient,
                                           const std::vector<float>& motion,
                                           const CompensationThresholds& thresholds,
                                           uint32_t seed) {
  CompensationCandidates out;
  out.added.sh_degree = moved.sh_degree;
  const size_t n = moved.size();
  out.removed.assign(n, 0);
  TrainingRandom rng(seed);
  for (size_t i = 0; i < n; ++i) {
    if (viewspace_gradient[i] > thresholds.gradient) {
      CopyGaussian(moved, i, &out.added);
      ++out.replicated;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    const float* o = &motion[7 * i];
    float translation = std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
    if (translation > thresholds.translation || IncrementAngle(o) > thresholds.rotation) {
      Split(moved, i, thresholds.split_scale_divisor, &rng, &out.added);
      out.removed[i] = 1;
      ++out.split;
    }
  }
  return out;
}

}  // namespace m4d
