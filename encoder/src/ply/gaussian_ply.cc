#include "encoder/src/ply/gaussian_ply.h"

#include <cmath>
#include <cstring>

#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/ply/ply_header.h"
#include "encoder/src/ply/ply_reader.h"

// Export copies floats as they are in memory.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "PLY export assumes a little-endian host");

namespace m4d {
namespace {

// Properties in file order, for the given number of f_rest values.
std::vector<std::string> PropertyNames(int rest_count, bool with_normals) {
  std::vector<std::string> names = {"x", "y", "z"};
  if (with_normals) names.insert(names.end(), {"nx", "ny", "nz"});
  names.insert(names.end(), {"f_dc_0", "f_dc_1", "f_dc_2"});
  for (int i = 0; i < rest_count; ++i) names.push_back("f_rest_" + std::to_string(i));
  names.insert(names.end(),
               {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"});
  return names;
}

// The SH degree whose higher coefficients fill rest_count f_rest values, or -1.
int DegreeForRestCount(int rest_count) {
  for (int degree = 0; degree <= 3; ++degree) {
    if (3 * (ShCoefficients(degree) - 1) == rest_count) return degree;
  }
  return -1;
}

Status CountRest(const PlyElement& vertex, int* rest_count) {
  int count = 0;
  for (const PlyProperty& property : vertex.properties) {
    if (property.name.compare(0, 7, "f_rest_") == 0) ++count;
  }
  for (int i = 0; i < count; ++i) {
    if (vertex.Find("f_rest_" + std::to_string(i)) < 0) {
      return BitstreamError("ply: f_rest properties are not f_rest_0..f_rest_" +
                            std::to_string(count - 1));
    }
  }
  *rest_count = count;
  return Status::Ok();
}

// Copies one row of values in PropertyNames order (without normals) into Gaussian g.
void StoreGaussian(const float* v, size_t g, int degree, GaussianSet* set) {
  const int rest = ShCoefficients(degree) - 1;
  std::memcpy(&set->positions[3 * g], v, 3 * sizeof(float));
  float* sh = &set->sh[g * set->sh_floats()];
  for (int c = 0; c < 3; ++c) sh[c] = v[3 + c];
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < rest; ++k) sh[3 * (k + 1) + c] = v[6 + c * rest + k];
  }
  const float* tail = v + 6 + 3 * rest;
  set->opacity_logits[g] = tail[0];
  std::memcpy(&set->log_scales[3 * g], tail + 1, 3 * sizeof(float));
  std::memcpy(&set->rotations[4 * g], tail + 4, 4 * sizeof(float));
}

Status CheckSet(const GaussianSet& set) {
  const size_t n = set.size();
  if (set.sh_degree < 0 || set.sh_degree > 3) {
    return Status(M4D_ERR_INVALID_ARG, "ply: SH degree must be 0..3");
  }
  if (set.positions.size() != 3 * n || set.log_scales.size() != 3 * n ||
      set.rotations.size() != 4 * n || set.sh.size() != static_cast<size_t>(set.sh_floats()) * n) {
    return Status(M4D_ERR_INVALID_ARG, "ply: Gaussian set arrays do not match its size");
  }
  return Status::Ok();
}

}  // namespace

Status DecodeGaussianPly(const uint8_t* data, size_t size, GaussianSet* set) {
  PlyHeader header;
  M4D_RETURN_IF_ERROR(ParsePlyHeader(data, size, &header));
  const int vertex = header.Find("vertex");
  if (vertex < 0) return BitstreamError("ply: no vertex element");
  int rest_count = 0;
  M4D_RETURN_IF_ERROR(CountRest(header.elements[vertex], &rest_count));
  const int degree = DegreeForRestCount(rest_count);
  if (degree < 0) {
    return Status(M4D_ERR_UNSUPPORTED,
                  "ply: " + std::to_string(rest_count) + " f_rest properties (not 0, 9, 24, 45)");
  }
  const std::vector<std::string> names = PropertyNames(rest_count, false);
  std::vector<float> values;
  size_t rows = 0;
  M4D_RETURN_IF_ERROR(ReadPlyProperties(data, size, header, "vertex", names, &values, &rows));
  for (float v : values) {
    if (!std::isfinite(v)) return BitstreamError("ply: non-finite Gaussian attribute");
  }
  set->sh_degree = degree;
  set->Resize(rows);
  for (size_t g = 0; g < rows; ++g) StoreGaussian(&values[g * names.size()], g, degree, set);
  return Status::Ok();
}

Status ReadGaussianPly(const std::string& path, GaussianSet* set) {
  std::vector<uint8_t> bytes;
  Status status = ReadFileBytes(path, kMaxPlyFileBytes, &bytes);
  if (status.ok()) status = DecodeGaussianPly(bytes.data(), bytes.size(), set);
  if (status.ok()) return status;
  return Status(status.code(), status.message() + " (" + path + ")");
}

Status EncodeGaussianPly(const GaussianSet& set, std::vector<uint8_t>* bytes) {
  M4D_RETURN_IF_ERROR(CheckSet(set));
  const int rest = ShCoefficients(set.sh_degree) - 1;
  const std::vector<std::string> names = PropertyNames(3 * rest, true);
  std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(set.size()) + "\n";
  for (const std::string& name : names) header += "property float " + name + "\n";
  header += "end_header\n";

  const size_t n = set.size();
  std::vector<float> row(names.size(), 0.0f);
  bytes->assign(header.begin(), header.end());
  bytes->resize(header.size() + n * row.size() * sizeof(float));
  uint8_t* out = bytes->data() + header.size();
  for (size_t g = 0; g < n; ++g) {
    const float* sh = &set.sh[g * set.sh_floats()];
    std::memcpy(row.data(), &set.positions[3 * g], 3 * sizeof(float));  // normals stay zero
    for (int c = 0; c < 3; ++c) row[6 + c] = sh[c];
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < rest; ++k) row[9 + c * rest + k] = sh[3 * (k + 1) + c];
    }
    float* tail = row.data() + 9 + 3 * rest;
    tail[0] = set.opacity_logits[g];
    std::memcpy(tail + 1, &set.log_scales[3 * g], 3 * sizeof(float));
    std::memcpy(tail + 4, &set.rotations[4 * g], 4 * sizeof(float));
    std::memcpy(out, row.data(), row.size() * sizeof(float));
    out += row.size() * sizeof(float);
  }
  return Status::Ok();
}

Status WriteGaussianPly(const std::string& path, const GaussianSet& set) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(EncodeGaussianPly(set, &bytes));
  return WriteFileBytes(path, bytes);
}

}  // namespace m4d
