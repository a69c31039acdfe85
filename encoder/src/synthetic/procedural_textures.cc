#include "encoder/src/synthetic/procedural_textures.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "encoder/src/synthetic/scene_random.h"
#include "encoder/src/synthetic/value_noise.h"

namespace m4d {
namespace {

constexpr float kTwoPi = 6.28318530718f;

float Fract(float x) { return x - std::floor(x); }

// 1 within half_width (in periods) of a multiple of the period, else 0.
float OnLine(float x, float period, float half_width) {
  const float f = Fract(x / period);
  return (f < half_width || f > 1.0f - half_width) ? 1.0f : 0.0f;
}

// Noise centred on zero, amplitude `a`, repeating over the unit square.
float Speckle(uint64_t seed, float u, float v, int cells, float a) {
  return a * (2.0f * FractalNoise(seed, u * cells, v * cells, cells, cells, 3) - 1.0f);
}

// A text-like glyph: a 5 x 7 bitmap chosen by `glyph`, drawn in a cell with one column and
// two rows of spacing. (cx, cy) in [0, 1) within the cell, cy up.
bool GlyphInk(uint64_t seed, uint64_t glyph, float cx, float cy) {
  const int col = static_cast<int>(cx * 6.0f), row = static_cast<int>(cy * 9.0f) - 1;
  if (col >= 5 || row < 0 || row >= 7) return false;
  return LatticeValue(seed ^ MixBits(glyph), col, row) < 0.42f;
}

// Rows of words in the rectangle [u0, u1] x [v0, v1]: `rows` lines, `columns` glyph cells
// per line, words of 2 to 8 glyphs separated by one blank cell.
bool TextInk(uint64_t seed, float u, float v, float u0, float u1, float v0, float v1, int rows,
             int columns) {
  if (u < u0 || u >= u1 || v < v0 || v >= v1) return false;
  const float x = (u - u0) / (u1 - u0) * columns, y = (v - v0) / (v1 - v0) * rows;
  const int cell = static_cast<int>(x), line = static_cast<int>(y);
  // Cells are blank where a word ends: about one in five, never two in a row.
  const bool blank =
      LatticeValue(seed + 1, cell, line) < 0.2f && LatticeValue(seed + 1, cell - 1, line) >= 0.2f;
  if (blank) return false;
  const uint64_t glyph = static_cast<uint64_t>(LatticeValue(seed + 2, cell, line) * 40.0f);
  return GlyphInk(seed, glyph, x - cell, y - line);
}

glm::vec3 Grey(float g) { return glm::vec3(g); }

}  // namespace

SceneTexture FloorTilesTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    const int i = static_cast<int>(u * 4), j = static_cast<int>(v * 4);
    const float lu = Fract(u * 4), lv = Fract(v * 4);
    if (lu < 0.025f || lu > 0.975f || lv < 0.025f || lv > 0.975f) {
      return glm::vec3(0.33f, 0.31f, 0.28f) + Speckle(seed, u, v, 128, 0.05f);
    }
    const bool cream = ((i + j) & 1) == 0;
    const float shade = 0.08f * (LatticeValue(seed + 3, i, j) - 0.5f);
    glm::vec3 c = cream ? glm::vec3(0.80f, 0.76f, 0.66f) : glm::vec3(0.60f, 0.32f, 0.22f);
    // Marble veins: thin bands of a warped noise field.
    const float warp = FractalNoise(seed + 5, u * 8, v * 8, 8, 8, 4);
    const float vein = std::fabs(std::sin((u * 6 + v * 3 + 3 * warp) * kTwoPi));
    if (vein < 0.08f) c *= cream ? 0.82f : 0.9f;
    return c + shade + Speckle(seed + 7, u, v, 64, 0.06f);
  });
}

SceneTexture WallpaperTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    glm::vec3 c = glm::vec3(0.55f, 0.62f, 0.50f) + Speckle(seed, u, v, 16, 0.05f);
    const float s = Fract(u * 16);
    if (s > 0.5f) c = glm::vec3(0.36f, 0.47f, 0.45f) + Speckle(seed + 1, u, v, 32, 0.04f);
    if (std::fabs(s - 0.5f) < 0.04f || s < 0.04f) c = glm::vec3(0.88f, 0.84f, 0.70f);
    // Small diamonds down the middle of the light bands.
    const float du = std::fabs(s - 0.25f) * 4, dv = std::fabs(Fract(v * 24) - 0.5f) * 2;
    if (du + dv < 0.45f) c = glm::vec3(0.75f, 0.55f, 0.30f);
    return c;
  });
}

SceneTexture BrickTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    const int row = static_cast<int>(v * 12);
    const float bu = u * 4 + ((row & 1) ? 0.5f : 0.0f);
    const int brick = static_cast<int>(std::floor(bu)) & 3;
    const float lu = Fract(bu), lv = Fract(v * 12);
    if (lu < 0.03f || lv < 0.09f) return Grey(0.62f) + Speckle(seed, u, v, 128, 0.06f);
    const float tone = LatticeValue(seed + 1, brick, row);
    const glm::vec3 c =
        glm::mix(glm::vec3(0.55f, 0.24f, 0.16f), glm::vec3(0.70f, 0.42f, 0.30f), tone);
    return c + Speckle(seed + 2, u, v, 64, 0.08f);
  });
}

SceneTexture CeilingTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    const float joint = std::max(OnLine(u, 0.5f, 0.01f), OnLine(v, 0.5f, 0.01f));
    return Grey(0.84f - 0.25f * joint) + Speckle(seed, u, v, 64, 0.05f);
  });
}

SceneTexture WoodTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    const float warp = FractalNoise(seed, u * 2, v * 8, 2, 8, 4);
    const float grain = 0.5f + 0.5f * std::sin((v * 24 + 5 * warp) * kTwoPi);
    const float streak = FractalNoise(seed + 1, u * 4, v * 128, 4, 128, 2);
    return glm::mix(glm::vec3(0.40f, 0.24f, 0.12f), glm::vec3(0.64f, 0.44f, 0.26f), grain) +
           0.12f * (streak - 0.5f);
  });
}

SceneTexture PlaidTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    glm::vec3 c(0.62f, 0.14f, 0.12f);
    if (Fract(u * 8) < 0.3f) c *= 0.6f;
    if (Fract(v * 8) < 0.3f) c *= 0.6f;
    if (std::fabs(Fract(u * 8) - 0.65f) < 0.04f || std::fabs(Fract(v * 8) - 0.65f) < 0.04f) {
      c = glm::vec3(0.85f, 0.75f, 0.25f);
    }
    return c + Speckle(seed, u, v, 32, 0.03f);
  });
}

SceneTexture DenimTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    const float twill = Fract((u + v) * 48) < 0.5f ? 0.06f : -0.04f;
    return glm::vec3(0.17f, 0.24f, 0.44f) + twill + Speckle(seed, u, v, 64, 0.06f);
  });
}

SceneTexture MetalTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    return Grey(0.55f) + 0.25f * (FractalNoise(seed, u * 2, v * 128, 2, 128, 3) - 0.5f);
  });
}

SceneTexture PosterTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    glm::vec3 paper = glm::vec3(0.92f, 0.89f, 0.80f) + Speckle(seed, u, v, 32, 0.03f);
    if (u < 0.03f || u > 0.97f || v < 0.03f || v > 0.97f) return glm::vec3(0.15f, 0.12f, 0.1f);
    if (v > 0.80f && v < 0.93f) {
      const bool ink = TextInk(seed + 10, u, v, 0.08f, 0.92f, 0.81f, 0.92f, 1, 10);
      return ink ? glm::vec3(0.65f, 0.10f, 0.08f) : paper;
    }
    // A picture on the right: a noise landscape.
    if (u > 0.62f && u < 0.92f && v > 0.35f && v < 0.75f) {
      const float n = FractalNoise(seed + 20, u * 16, v * 16, 16, 16, 4);
      return glm::mix(glm::vec3(0.2f, 0.35f, 0.6f), glm::vec3(0.3f, 0.6f, 0.25f), n);
    }
    const float body_u1 = v > 0.35f && v < 0.75f ? 0.58f : 0.92f;
    const bool ink = TextInk(seed + 30, u, v, 0.08f, body_u1, 0.08f, 0.75f, 22, 36);
    return ink ? glm::vec3(0.08f, 0.08f, 0.1f) : paper;
  });
}

SceneTexture RugTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    const float wool = Speckle(seed, u, v, 128, 0.05f);
    const float edge = std::min(std::min(u, 1 - u), std::min(v, 1 - v));
    if (edge < 0.09f) {
      const bool gold = std::fabs(edge - 0.045f) < 0.008f || OnLine(u + v, 0.04f, 0.12f) > 0 ||
                        OnLine(u - v, 0.04f, 0.12f) > 0;
      return (gold && edge > 0.02f ? glm::vec3(0.80f, 0.62f, 0.25f)
                                   : glm::vec3(0.10f, 0.14f, 0.32f)) +
             wool;
    }
    const float d = std::fabs(Fract(u * 10) - 0.5f) + std::fabs(Fract(v * 7) - 0.5f);
    glm::vec3 c = d < 0.2f   ? glm::vec3(0.85f, 0.80f, 0.65f)
                  : d < 0.3f ? glm::vec3(0.15f, 0.12f, 0.12f)
                             : glm::vec3(0.58f, 0.12f, 0.10f);
    return c + wool;
  });
}

SceneTexture BookSpinesTexture(uint64_t seed) {
  return MakeTexture(512, 512, [seed](float u, float v) {
    const int book = static_cast<int>(u * 16);
    const float lu = Fract(u * 16);
    const glm::vec3 palette[6] = {{0.55f, 0.12f, 0.10f}, {0.12f, 0.25f, 0.45f},
                                  {0.15f, 0.38f, 0.20f}, {0.60f, 0.50f, 0.30f},
                                  {0.30f, 0.15f, 0.35f}, {0.80f, 0.75f, 0.65f}};
    const glm::vec3 base = palette[MixBits(seed + book) % 6];
    if (std::fabs(v - 0.86f) < 0.015f || std::fabs(v - 0.14f) < 0.015f) {
      return glm::vec3(0.82f, 0.66f, 0.28f);
    }
    // The title runs up the spine: glyph cells along v.
    const bool ink =
        lu > 0.3f && lu < 0.7f && v > 0.3f && v < 0.75f &&
        GlyphInk(seed + book, static_cast<uint64_t>(v * 16), Fract(v * 16), (lu - 0.3f) / 0.4f);
    const glm::vec3 title = base.r + base.g + base.b > 1.5f ? glm::vec3(0.1f) : glm::vec3(0.9f);
    return (ink ? title : base) + Speckle(seed, u, v, 64, 0.03f);
  });
}

SceneTexture SkinTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    if (v > 0.70f) {
      return glm::vec3(0.22f, 0.14f, 0.08f) +
             0.12f * (FractalNoise(seed, u * 64, v * 8, 64, 8, 2) - 0.5f);
    }
    // u = 0 faces forward (+z); distance around the head from the front.
    const float du = std::min(u, 1 - u);
    const bool eye = std::fabs(v - 0.57f) < 0.035f && std::fabs(du - 0.07f) < 0.025f;
    const bool mouth = std::fabs(v - 0.40f) < 0.015f && du < 0.05f;
    if (eye) return glm::vec3(0.08f, 0.06f, 0.05f);
    if (mouth) return glm::vec3(0.55f, 0.20f, 0.18f);
    return glm::vec3(0.85f, 0.64f, 0.50f) + Speckle(seed + 1, u, v, 32, 0.03f);
  });
}

SceneTexture PatternedCubeTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    if (u < 0.06f || u > 0.94f || v < 0.06f || v > 0.94f) return glm::vec3(0.10f, 0.10f, 0.12f);
    if (u > 0.3f && u < 0.7f && v > 0.25f && v < 0.75f &&
        GlyphInk(seed, 7, (u - 0.3f) / 0.4f, (v - 0.25f) / 0.5f)) {
      return glm::vec3(0.70f, 0.10f, 0.30f);
    }
    const bool check = ((static_cast<int>(u * 8) + static_cast<int>(v * 8)) & 1) != 0;
    return check ? glm::vec3(0.90f, 0.78f, 0.20f) : glm::vec3(0.10f, 0.55f, 0.55f);
  });
}

SceneTexture BeachBallTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    if (v < 0.08f || v > 0.92f) return glm::vec3(0.92f) + Speckle(seed, u, v, 16, 0.02f);
    const glm::vec3 gores[6] = {{0.85f, 0.12f, 0.10f}, {0.92f, 0.92f, 0.90f},
                                {0.10f, 0.30f, 0.80f}, {0.95f, 0.80f, 0.10f},
                                {0.15f, 0.60f, 0.20f}, {0.95f, 0.50f, 0.10f}};
    if (OnLine(u, 1.0f / 6, 0.04f) > 0) return glm::vec3(0.2f);
    return gores[static_cast<int>(u * 6) % 6];
  });
}

SceneTexture LampShadeTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    const float rib = Fract(u * 48) < 0.15f ? -0.08f : 0.0f;
    return glm::vec3(0.95f, 0.90f, 0.78f) + rib + Speckle(seed, u, v, 32, 0.02f);
  });
}

SceneTexture LeavesTexture(uint64_t seed) {
  return MakeTexture(256, 256, [seed](float u, float v) {
    // Cells of a noise field read as leaves, their borders as the dark gaps between them.
    const float n = FractalNoise(seed, u * 12, v * 12, 12, 12, 3);
    const float light = 0.5f + 0.5f * std::sin(n * 40.0f);
    return glm::mix(glm::vec3(0.08f, 0.22f, 0.06f), glm::vec3(0.30f, 0.55f, 0.18f), light) +
           Speckle(seed + 1, u, v, 64, 0.03f);
  });
}

}  // namespace m4d
