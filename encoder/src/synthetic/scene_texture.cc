#include "encoder/src/synthetic/scene_texture.h"

#include <cmath>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/metrics/parallel_rows.h"

namespace m4d {
namespace {

int Wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

glm::vec3 Texel(const SceneTexture& texture, int x, int y) {
  const uint8_t* p = &texture.rgb[(static_cast<size_t>(y) * texture.width + x) * 3];
  return glm::vec3(ByteToFloat(p[0]), ByteToFloat(p[1]), ByteToFloat(p[2]));
}

}  // namespace

SceneTexture MakeTexture(int width, int height,
                         const std::function<glm::vec3(float u, float v)>& colour) {
  SceneTexture texture;
  texture.width = width;
  texture.height = height;
  texture.rgb.resize(static_cast<size_t>(width) * height * 3);
  ParallelForRows(height, static_cast<size_t>(width) * 64, [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      uint8_t* row = &texture.rgb[static_cast<size_t>(y) * width * 3];
      const float v = (y + 0.5f) / height;
      for (int x = 0; x < width; ++x) {
        const glm::vec3 c = colour((x + 0.5f) / width, v);
        row[3 * x] = FloatToByte(c.r);
        row[3 * x + 1] = FloatToByte(c.g);
        row[3 * x + 2] = FloatToByte(c.b);
      }
    }
  });
  return texture;
}

glm::vec3 SampleTexture(const SceneTexture& texture, float u, float v) {
  // Texel centres sit at (i + 0.5) / size, as in GL.
  const float x = u * texture.width - 0.5f, y = v * texture.height - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = Wrap(static_cast<int>(fx), texture.width);
  const int y0 = Wrap(static_cast<int>(fy), texture.height);
  const int x1 = Wrap(x0 + 1, texture.width), y1 = Wrap(y0 + 1, texture.height);
  const glm::vec3 top = Texel(texture, x0, y0) * (1 - tx) + Texel(texture, x1, y0) * tx;
  const glm::vec3 bottom = Texel(texture, x0, y1) * (1 - tx) + Texel(texture, x1, y1) * tx;
  return top * (1 - ty) + bottom * ty;
}

}  // namespace m4d
