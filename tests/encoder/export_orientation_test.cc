// Export orientation and colour: the stream's up axis becomes -y in PLY and +y in glTF, with
// each Gaussian's rotation and view-dependent colour turned consistently; COLOR_0 is linear,
// every bufferView has its target, and an empty set is refused in plain words.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>

#include "encoder/src/export/axis_rotation.h"
#include "encoder/src/export/gltf_splat_writer.h"
#include "encoder/src/export/sh_rotation.h"
#include "encoder/src/export/turn_gaussians.h"
#include "m4d/m4d.h"
#include "sdk/src/render/sh_evaluation.h"

namespace m4d {
namespace {

void Apply(const AxisRotation& r, const float v[3], float out[3]) {
  for (int i = 0; i < 3; ++i)
    out[i] = r.m[3 * i] * v[0] + r.m[3 * i + 1] * v[1] + r.m[3 * i + 2] * v[2];
}

// Row-major rotation matrix of a unit quaternion (w, x, y, z).
void QuaternionMatrix(const float q[4], double m[9]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  const double a = w / n, b = x / n, c = y / n, d = z / n;
  const double r[9] = {1 - 2 * (c * c + d * d), 2 * (b * c - a * d),     2 * (b * d + a * c),
                       2 * (b * c + a * d),     1 - 2 * (b * b + d * d), 2 * (c * d - a * b),
                       2 * (b * d - a * c),     2 * (c * d + a * b),     1 - 2 * (b * b + c * c)};
  std::memcpy(m, r, sizeof(r));
}

TEST(ExportOrientation, RotationsTakeEveryAxisToEveryAxis) {
  for (int from = 1; from <= 6; ++from) {
    for (int to = 1; to <= 6; ++to) {
      const AxisRotation r = RotationBetweenAxes(from, to);
      float f[3], t[3], moved[3];
      UpAxisVector(from, f);
      UpAxisVector(to, t);
      Apply(r, f, moved);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(moved[i], t[i]) << from << " to " << to;
      const float* m = r.m;  // a rotation, not a mirror
      const float det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                        m[2] * (m[3] * m[7] - m[4] * m[6]);
      EXPECT_EQ(det, 1.0f);
    }
  }
}

TEST(ExportOrientation, UpBecomesMinusYInPlyAndPlusYInGltf) {
  for (int up = 1; up <= 6; ++up) {
    float u[3], ply[3], gltf[3];
    UpAxisVector(up, u);  // a Gaussian one unit above the centre
    Apply(PlyFrame(up), u, ply);
    Apply(GltfFrame(up), u, gltf);
    EXPECT_EQ(ply[1], -1.0f) << up;
    EXPECT_EQ(gltf[1], 1.0f) << up;
  }
  // Not stated: taken as -y, so PLY keeps the stream's frame and glTF gets splat-transform's
  // turn of a PLY (180 degrees about z).
  EXPECT_TRUE(PlyFrame(M4D_UP_UNKNOWN).is_identity());
  EXPECT_TRUE(PlyFrame(M4D_UP_NEG_Y).is_identity());
  const float rz180[9] = {-1, 0, 0, 0, -1, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(GltfFrame(M4D_UP_UNKNOWN).m[i], rz180[i]);
    EXPECT_EQ(GltfFrame(M4D_UP_NEG_Y).m[i], rz180[i]);
  }
  EXPECT_TRUE(GltfFrame(M4D_UP_POS_Y).is_identity());
}

// What splat-transform 2.7.1 writes when it turns a PLY Gaussian into glTF (measured): position
// (x, y, z) -> (-x, -y, z), quaternion (w, x, y, z) = (0.9, 0.1, 0.2, 0.3) -> (-0.3, -0.2,
// 0.1, 0.9), degree-1 SH (0.1, 0.2, 0.3) -> (-0.1, 0.2, -0.3).
TEST(ExportOrientation, MatchesSplatTransformOnAKnownGaussian) {
  GaussianSet set;
  set.sh_degree = 1;
  set.Resize(1);
  const float p[3] = {1, -2, 3}, q[4] = {0.9f, 0.1f, 0.2f, 0.3f};
  std::copy(p, p + 3, set.positions.begin());
  std::copy(q, q + 4, set.rotations.begin());
  std::fill(set.sh.begin(), set.sh.end(), 0.0f);
  set.sh[3] = 0.1f, set.sh[6] = 0.2f, set.sh[9] = 0.3f;  // red, coefficients 1..3
  TurnGaussians(GltfFrame(M4D_UP_NEG_Y), &set);
  EXPECT_FLOAT_EQ(set.positions[0], -1);
  EXPECT_FLOAT_EQ(set.positions[1], 2);
  EXPECT_FLOAT_EQ(set.positions[2], 3);
  const float want_q[4] = {-0.3f, -0.2f, 0.1f, 0.9f};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(set.rotations[i], want_q[i], 1e-6) << i;
  EXPECT_FLOAT_EQ(set.sh[3], -0.1f);
  EXPECT_FLOAT_EQ(set.sh[6], 0.2f);
  EXPECT_FLOAT_EQ(set.sh[9], -0.3f);
}

// Render equivalence for every turn: the colour seen along R d equals the colour before along
// d, and the Gaussian's axes turn with the world (R_g' = R R_g).
TEST(ExportOrientation, RotationAndShTurnWithTheWorld) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int up = 1; up <= 6; ++up) {
    const AxisRotation r = GltfFrame(up);
    GaussianSet set;
    set.sh_degree = 3;
    set.Resize(1);
    for (float& v : set.sh) v = u(rng);
    for (float& v : set.rotations) v = u(rng);
    const GaussianSet before = set;
    TurnGaussians(r, &set);
    for (int trial = 0; trial < 8; ++trial) {
      float d[3] = {u(rng), u(rng), u(rng)};
      const float n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (float& v : d) v /= n;
      float turned[3], b0[kMaxShCoefficients], b1[kMaxShCoefficients], c0[3], c1[3];
      Apply(r, d, turned);
      ShBasis(3, d[0], d[1], d[2], b0);
      ShBasis(3, turned[0], turned[1], turned[2], b1);
      ShColour(b0, 16, before.sh.data(), c0);
      ShColour(b1, 16, set.sh.data(), c1);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(c1[c], c0[c], 1e-5) << "up " << up;
    }
    double g0[9], g1[9];
    QuaternionMatrix(before.rotations.data(), g0);
    QuaternionMatrix(set.rotations.data(), g1);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        double want = 0;
        for (int k = 0; k < 3; ++k) want += r.m[3 * i + k] * g0[3 * k + j];
        EXPECT_NEAR(g1[3 * i + j], want, 1e-6) << "up " << up;
      }
    }
  }
}

nlohmann::json GlbJson(const std::vector<uint8_t>& glb, std::vector<float>* bin) {
  uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const std::string text(glb.begin() + 20, glb.begin() + 20 + json_length);
  const size_t bin_start = 20 + json_length + 8;
  bin->resize((glb.size() - bin_start) / 4);
  std::memcpy(bin->data(), glb.data() + bin_start, bin->size() * 4);
  return nlohmann::json::parse(text);
}

TEST(ExportGlb, ColourIsLinearAndViewsHaveTargets) {
  GaussianSet set;
  set.sh_degree = 0;
  set.Resize(1);
  std::fill(set.positions.begin(), set.positions.end(), 0.0f);
  std::fill(set.log_scales.begin(), set.log_scales.end(), 0.0f);
  set.rotations[0] = 1, set.rotations[1] = set.rotations[2] = set.rotations[3] = 0;
  set.opacity_logits[0] = 0;
  // sRGB 0.5, 1 and 0.02 (below the linear segment's knee): SH DC (v - 0.5) / C0.
  const float srgb[3] = {0.5f, 1.0f, 0.02f}, linear[3] = {0.21404f, 1.0f, 0.02f / 12.92f};
  for (int c = 0; c < 3; ++c) set.sh[c] = (srgb[c] - 0.5f) / kShC0;
  std::vector<uint8_t> glb;
  ASSERT_TRUE(EncodeGaussianGlb(set, &glb).ok());
  std::vector<float> bin;
  const nlohmann::json doc = GlbJson(glb, &bin);
  for (const auto& view : doc["bufferViews"]) EXPECT_EQ(view["target"], 34962);  // ARRAY_BUFFER
  const int accessor = doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"];
  const int view = doc["accessors"][accessor]["bufferView"];
  const size_t offset = doc["bufferViews"][view]["byteOffset"].get<size_t>() / 4;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(bin[offset + c], linear[c], 1e-5) << c;
  EXPECT_FLOAT_EQ(bin[offset + 3], 0.5f);  // opacity, not a colour
}

TEST(ExportGlb, EmptySetIsRefusedInPlainWords) {
  GaussianSet empty;
  std::vector<uint8_t> glb;
  const Status status = EncodeGaussianGlb(empty, &glb);
  EXPECT_EQ(status.code(), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(status.message().find("Encode"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("no Gaussians"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace m4d
