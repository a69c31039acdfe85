#include "encoder/src/export/gltf_splat_writer.h"

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "encoder/src/export/srgb.h"
#include "encoder/src/io/atomic_file.h"

namespace m4d {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;
constexpr int kFloat = 5126;         // accessor componentType
constexpr int kArrayBuffer = 34962;  // bufferView target of vertex attributes
constexpr float kShC0 = 0.28209479177387814f;

struct Attribute {
  std::string name;
  int components = 0;
  std::vector<float> values;  // count * components
};

const char* AccessorType(int components) {
  return components == 1 ? "SCALAR" : components == 3 ? "VEC3" : "VEC4";
}

float Sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

// The diffuse colour as glTF's COLOR_0 wants it: linear, though the SH values are sRGB.
float DiffuseLinear(float sh_dc) {
  return SrgbToLinear(std::fmin(1.0f, std::fmax(0.0f, 0.5f + kShC0 * sh_dc)));
}

// Every attribute of the extension from the set's coded values.
std::vector<Attribute> Attributes(const GaussianSet& set) {
  const size_t n = set.size();
  const int coefficients = ShCoefficients(set.sh_degree);
  const size_t sh_stride = static_cast<size_t>(set.sh_floats());
  std::vector<Attribute> out = {{"POSITION", 3, {}},
                                {"COLOR_0", 4, {}},
                                {"KHR_gaussian_splatting:ROTATION", 4, {}},
                                {"KHR_gaussian_splatting:SCALE", 3, {}},
                                {"KHR_gaussian_splatting:OPACITY", 1, {}}};
  for (int k = 0; k < coefficients; ++k) {
    const int degree = static_cast<int>(std::sqrt(static_cast<double>(k)) + 1e-9);
    out.push_back({"KHR_gaussian_splatting:SH_DEGREE_" + std::to_string(degree) + "_COEF_" +
                       std::to_string(k - degree * degree),
                   3,
                   {}});
  }
  for (Attribute& a : out) a.values.reserve(n * static_cast<size_t>(a.components));
  for (size_t i = 0; i < n; ++i) {
    const float* p = &set.positions[3 * i];
    const float* q = &set.rotations[4 * i];  // w, x, y, z
    const float* sh = &set.sh[i * sh_stride];
    const float opacity = Sigmoid(set.opacity_logits[i]);
    out[0].values.insert(out[0].values.end(), p, p + 3);
    for (int c = 0; c < 3; ++c) {
      out[1].values.push_back(DiffuseLinear(sh[c]));
    }
    out[1].values.push_back(opacity);
    const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const float unit[4] = {norm > 0 ? q[1] / norm : 0.0f, norm > 0 ? q[2] / norm : 0.0f,
                           norm > 0 ? q[3] / norm : 0.0f, norm > 0 ? q[0] / norm : 1.0f};
    out[2].values.insert(out[2].values.end(), unit, unit + 4);
    for (int a = 0; a < 3; ++a) out[3].values.push_back(std::exp(set.log_scales[3 * i + a]));
    out[4].values.push_back(opacity);
    for (int k = 0; k < coefficients; ++k) {
      out[5 + static_cast<size_t>(k)].values.insert(out[5 + static_cast<size_t>(k)].values.end(),
                                                    sh + 3 * k, sh + 3 * k + 3);
    }
  }
  return out;
}

void AppendU32(uint32_t v, std::vector<uint8_t>* bytes) {
  for (int i = 0; i < 4; ++i) bytes->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void AppendChunk(uint32_t type, std::vector<uint8_t> data, uint8_t pad,
                 std::vector<uint8_t>* bytes) {
  while (data.size() % 4 != 0) data.push_back(pad);
  AppendU32(static_cast<uint32_t>(data.size()), bytes);
  AppendU32(type, bytes);
  bytes->insert(bytes->end(), data.begin(), data.end());
}

}  // namespace

Status EncodeGaussianGlb(const GaussianSet& set, std::vector<uint8_t>* bytes) {
  const size_t n = set.size();
  if (n == 0) {
    return Status(M4D_ERR_INVALID_ARG, "no Gaussians to write: glTF has no empty point primitive");
  }
  if (set.sh_degree < 0 || set.sh_degree > 3 || set.positions.size() != 3 * n ||
      set.log_scales.size() != 3 * n || set.rotations.size() != 4 * n ||
      set.sh.size() != static_cast<size_t>(set.sh_floats()) * n) {
    return Status(M4D_ERR_INVALID_ARG, "the Gaussian arrays do not match the set's size");
  }
  using nlohmann::json;
  const std::vector<Attribute> attributes = Attributes(set);
  std::vector<uint8_t> bin;
  json views = json::array(), accessors = json::array(), semantics = json::object();
  for (const Attribute& a : attributes) {
    const size_t offset = bin.size(), length = a.values.size() * sizeof(float);
    bin.resize(offset + length);
    std::memcpy(bin.data() + offset, a.values.data(), length);
    json accessor = {{"bufferView", views.size()},
                     {"componentType", kFloat},
                     {"count", n},
                     {"type", AccessorType(a.components)}};
    if (a.name == "POSITION") {  // required by glTF for positions
      json lo = json::array(), hi = json::array();
      for (int c = 0; c < 3; ++c) {
        float mn = a.values[c], mx = a.values[c];
        for (size_t i = 0; i < n; ++i) {
          mn = std::fmin(mn, a.values[3 * i + c]);
          mx = std::fmax(mx, a.values[3 * i + c]);
        }
        lo.push_back(mn);
        hi.push_back(mx);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    semantics[a.name] = accessors.size();
    accessors.push_back(accessor);
    views.push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", kArrayBuffer}});
  }
  const json primitive = {{"attributes", semantics},
                          {"mode", 0},  // POINTS
                          {"extensions",
                           {{"KHR_gaussian_splatting",
                             {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"}}}}}};
  const json doc = {{"asset", {{"version", "2.0"}, {"generator", "m4d"}}},
                    {"extensionsUsed", {"KHR_gaussian_splatting"}},
                    {"scene", 0},
                    {"scenes", {{{"nodes", {0}}}}},
                    {"nodes", {{{"mesh", 0}}}},
                    {"meshes", {{{"primitives", {primitive}}}}},
                    {"buffers", {{{"byteLength", bin.size()}}}},
                    {"bufferViews", views},
                    {"accessors", accessors}};
  const std::string text = doc.dump();
  bytes->clear();
  AppendU32(kGlbMagic, bytes);
  AppendU32(2, bytes);
  AppendU32(0, bytes);  // total length, set below
  AppendChunk(kChunkJson, std::vector<uint8_t>(text.begin(), text.end()), ' ', bytes);
  AppendChunk(kChunkBin, std::move(bin), 0, bytes);
  const uint32_t total = static_cast<uint32_t>(bytes->size());
  for (int i = 0; i < 4; ++i) (*bytes)[8 + i] = static_cast<uint8_t>(total >> (8 * i));
  return Status::Ok();
}

Status WriteGaussianGlb(const std::string& path, const GaussianSet& set) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(EncodeGaussianGlb(set, &bytes));
  return WriteFileAtomically(path, bytes.data(), bytes.size());
}

}  // namespace m4d
