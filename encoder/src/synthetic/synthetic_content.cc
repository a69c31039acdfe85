#include "encoder/src/synthetic/synthetic_content.h"

#include <cmath>

namespace m4d {

GaussianSet SyntheticGaussianSet(size_t n, int sh_degree, uint64_t seed, const float center[3],
                                 float radius) {
  SyntheticRandom rng(seed);
  GaussianSet set;
  set.sh_degree = sh_degree;
  set.Resize(n);
  const int coeffs = ShCoefficients(sh_degree);
  for (size_t i = 0; i < n; ++i) {
    // A point on the sphere from a normalised random direction.
    float d[3], len2 = 0;
    do {
      len2 = 0;
      for (float& c : d) {
        c = rng.Uniform(-1, 1);
        len2 += c * c;
      }
    } while (len2 < 1e-4f || len2 > 1);
    const float inv = 1.0f / std::sqrt(len2);
    for (int a = 0; a < 3; ++a) {
      set.positions[3 * i + a] = center[a] + radius * d[a] * inv * rng.Uniform(0.97f, 1.03f);
      set.log_scales[3 * i + a] = rng.Uniform(-5.5f, -3.0f);
    }
    float q[4], qn = 0;
    for (float& c : q) {
      c = rng.Uniform(-1, 1);
      qn += c * c;
    }
    qn = std::sqrt(qn) + 1e-6f;
    for (int k = 0; k < 4; ++k) set.rotations[4 * i + k] = q[k] / qn;
    set.opacity_logits[i] = rng.Uniform(-2, 4);
    float* sh = &set.sh[static_cast<size_t>(3 * coeffs) * i];
    for (int c = 0; c < 3; ++c) sh[c] = 0.8f * d[c] * inv + rng.Uniform(-0.1f, 0.1f);
    for (int k = 1; k < coeffs; ++k) {
      for (int c = 0; c < 3; ++c) sh[3 * k + c] = rng.Uniform(-0.2f, 0.2f) / static_cast<float>(k);
    }
  }
  return set;
}

FloatMotionGrid SyntheticMotionGrid(const GridConfig& config, uint64_t seed, float lo, float hi,
                                    float blob_fraction) {
  SyntheticRandom rng(seed);
  FloatMotionGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.box_min[a] = lo;
    grid.box_scale[a] = 1.0f / (hi - lo);
  }
  // A ball of the given volume fraction, somewhere inside the unit box.
  const float radius = std::cbrt(blob_fraction * 3.0f / (4.0f * 3.14159265f));
  float blob[3];
  for (float& c : blob) c = rng.Uniform(radius, 1 - radius);
  for (int l = 0; l < config.num_levels; ++l) {
    const int r = config.resolution[l], channels = config.channels[l];
    grid.step[l] = 1.0f / 64;
    grid.values[l].assign(config.level_values(l), 0.0f);
    float phase[kMaxGridChannels];
    for (int c = 0; c < channels; ++c) phase[c] = rng.Uniform(0, 6.28f);
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          const float p[3] = {x / (r - 1.0f), y / (r - 1.0f), z / (r - 1.0f)};
          float d2 = 0;
          for (int a = 0; a < 3; ++a) d2 += (p[a] - blob[a]) * (p[a] - blob[a]);
          const float falloff = 1.0f - d2 / (radius * radius);
          if (falloff <= 0) continue;
          for (int c = 0; c < channels; ++c) {
            const size_t index = ((static_cast<size_t>(z) * r + y) * r + x) * channels + c;
            grid.values[l][index] = 0.5f * falloff * std::sin(phase[c] + 4.0f * p[0] + 3.0f * p[1]);
          }
        }
      }
    }
  }
  return grid;
}

MlpWeights SyntheticMlp(int feature_count, const MlpConfig& config, uint64_t seed) {
  SyntheticRandom rng(seed);
  MlpWeights mlp;
  mlp.layers = MlpShapes(feature_count, config);
  for (MlpLayer& layer : mlp.layers) {
    const float bound = 1.0f / std::sqrt(static_cast<float>(layer.inputs));
    layer.weights.resize(static_cast<size_t>(layer.inputs) * layer.outputs);
    layer.biases.resize(static_cast<size_t>(layer.outputs));
    for (float& w : layer.weights) w = rng.Uniform(-bound, bound);
    for (float& b : layer.biases) b = rng.Uniform(-0.01f, 0.01f);
  }
  return mlp;
}

}  // namespace m4d
