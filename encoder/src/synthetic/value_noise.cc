#include "encoder/src/synthetic/value_noise.h"

#include <cmath>

#include "encoder/src/synthetic/scene_random.h"

namespace m4d {
namespace {

int Wrap(int64_t v, int period) {
  const int64_t m = v % period;
  return static_cast<int>(m < 0 ? m + period : m);
}

float Smooth(float t) { return t * t * (3.0f - 2.0f * t); }

}  // namespace

float ValueNoise(uint64_t seed, float x, float y, int period_x, int period_y) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
  const float tx = Smooth(x - fx), ty = Smooth(y - fy);
  const int x0 = Wrap(ix, period_x), x1 = Wrap(ix + 1, period_x);
  const int y0 = Wrap(iy, period_y), y1 = Wrap(iy + 1, period_y);
  const float a = LatticeValue(seed, x0, y0), b = LatticeValue(seed, x1, y0);
  const float c = LatticeValue(seed, x0, y1), d = LatticeValue(seed, x1, y1);
  const float top = a + (b - a) * tx, bottom = c + (d - c) * tx;
  return top + (bottom - top) * ty;
}

float FractalNoise(uint64_t seed, float x, float y, int period_x, int period_y, int octaves) {
  float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * ValueNoise(seed + static_cast<uint64_t>(o), x, y, period_x, period_y);
    total += amplitude;
    amplitude *= 0.5f;
    x *= 2.0f;
    y *= 2.0f;
    period_x *= 2;
    period_y *= 2;
  }
  return sum / total;
}

}  // namespace m4d
