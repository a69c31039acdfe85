// Export of decoded frames: the 3DGS PLY reads back to the very values decoded, and the glTF
// file is a well-formed GLB with the KHR_gaussian_splatting attributes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "encoder/src/export/frame_gaussians.h"
#include "encoder/src/export/gltf_splat_writer.h"
#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/ply/gaussian_ply.h"
#include "m4d/m4d.h"

namespace m4d {
namespace {

// Decodes `stream` and returns a copy of frame `index` as a set with both layers.
GaussianSet DecodedFrame(const std::string& stream, uint32_t index, size_t* static_count) {
  std::vector<uint8_t> data;
  EXPECT_TRUE(ReadFileBytes(stream, SIZE_MAX / 2, &data).ok());
  M4dSettings settings;
  m4d_default_settings(&settings);
  M4dContext* ctx = nullptr;
  EXPECT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  GaussianSet set;
  size_t pos = 0;
  while (pos < data.size()) {
    M4dPacketInfo info;
    if (m4d_parse_packet_header(&data[pos], data.size() - pos, &info) != M4D_OK) {
      ADD_FAILURE() << "bad packet at byte " << pos;
      break;
    }
    EXPECT_EQ(m4d_send_packet(ctx, &data[pos], info.packet_size), M4D_OK);
    pos += info.packet_size;
    M4dFrame frame;
    if (m4d_get_frame(ctx, &frame) != M4D_OK) continue;
    if (frame.frame_index == index) {
      EXPECT_TRUE(GaussianSetFromFrame(frame, M4D_LAYER_ALL, &set).ok());
      *static_count = frame.static_layer.count;
      EXPECT_EQ(set.size(),
                static_cast<size_t>(frame.static_layer.count) + frame.dynamic_layer.count);
    }
    m4d_frame_unref(&frame);
  }
  m4d_close(&ctx);
  return set;
}

const std::string kStream =
    std::string(M4D_SOURCE_DIR) + "/conformance/streams/synth_sh3_three_gops.m4d";

template <typename A, typename B>
bool SameFloats(const A& a, const B& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(FrameExport, PlyReadsBackToTheDecodedValues) {
  size_t static_count = 0;
  const GaussianSet set = DecodedFrame(kStream, 2, &static_count);
  ASSERT_GT(static_count, 0u);
  ASSERT_GT(set.size(), static_count);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(EncodeGaussianPly(set, &bytes).ok());
  GaussianSet back;
  ASSERT_TRUE(DecodeGaussianPly(bytes.data(), bytes.size(), &back).ok());
  EXPECT_EQ(back.sh_degree, set.sh_degree);
  EXPECT_TRUE(SameFloats(back.positions, set.positions));
  EXPECT_TRUE(SameFloats(back.log_scales, set.log_scales));
  EXPECT_TRUE(SameFloats(back.rotations, set.rotations));
  EXPECT_TRUE(SameFloats(back.opacity_logits, set.opacity_logits));
  EXPECT_TRUE(SameFloats(back.sh, set.sh));
}

uint32_t U32(const std::vector<uint8_t>& b, size_t at) {
  return b[at] | b[at + 1] << 8 | b[at + 2] << 16 | static_cast<uint32_t>(b[at + 3]) << 24;
}

TEST(FrameExport, GlbCarriesTheSplatAttributes) {
  size_t static_count = 0;
  const GaussianSet set = DecodedFrame(kStream, 2, &static_count);
  std::vector<uint8_t> glb;
  ASSERT_TRUE(EncodeGaussianGlb(set, &glb).ok());
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(U32(glb, 0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(U32(glb, 4), 2u);
  EXPECT_EQ(U32(glb, 8), glb.size());
  const uint32_t json_length = U32(glb, 12);
  EXPECT_EQ(U32(glb, 16), 0x4E4F534Au);
  const nlohmann::json doc =
      nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + json_length);
  const size_t bin_at = 20 + json_length + 8;
  EXPECT_EQ(U32(glb, 20 + json_length + 4), 0x004E4942u);
  EXPECT_EQ(doc["extensionsUsed"][0], "KHR_gaussian_splatting");
  const nlohmann::json& primitive = doc["meshes"][0]["primitives"][0];
  EXPECT_EQ(primitive["mode"], 0);
  EXPECT_EQ(primitive["extensions"]["KHR_gaussian_splatting"]["kernel"], "ellipse");
  const nlohmann::json& attributes = primitive["attributes"];
  EXPECT_EQ(attributes.size(), 5u + 16u);  // SH degree 3: 16 coefficients
  EXPECT_TRUE(attributes.contains("KHR_gaussian_splatting:SH_DEGREE_3_COEF_6"));
  // The first Gaussian's values, activated as the extension defines them.
  auto value = [&](const char* name, int component) {
    const nlohmann::json& accessor = doc["accessors"][attributes[name].get<size_t>()];
    EXPECT_EQ(accessor["count"], set.size());
    const nlohmann::json& view = doc["bufferViews"][accessor["bufferView"].get<size_t>()];
    float v;
    std::memcpy(&v, &glb[bin_at + view["byteOffset"].get<size_t>() + 4 * component], 4);
    return v;
  };
  const float* q = &set.rotations[0];
  const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  EXPECT_FLOAT_EQ(value("KHR_gaussian_splatting:ROTATION", 3), q[0] / norm);  // w last
  EXPECT_FLOAT_EQ(value("KHR_gaussian_splatting:ROTATION", 0), q[1] / norm);
  EXPECT_FLOAT_EQ(value("KHR_gaussian_splatting:SCALE", 2), std::exp(set.log_scales[2]));
  EXPECT_FLOAT_EQ(value("KHR_gaussian_splatting:OPACITY", 0),
                  1.0f / (1.0f + std::exp(-set.opacity_logits[0])));
  EXPECT_EQ(value("KHR_gaussian_splatting:SH_DEGREE_1_COEF_2", 1), set.sh[3 * 3 + 1]);
  EXPECT_EQ(value("POSITION", 1), set.positions[1]);
  EXPECT_FALSE(EncodeGaussianGlb(GaussianSet(), &glb).ok());
}

}  // namespace
}  // namespace m4d
