#include "encoder/src/train/gaussian_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "encoder/src/train/row_edit.h"

namespace m4d {

int GaussianModel::width(GaussianParameter p) const {
  switch (p) {
    case kParamPositions:
    case kParamLogScales:
      return 3;
    case kParamRotations:
      return 4;
    case kParamOpacityLogits:
      return 1;
    default:
      return sh_floats();
  }
}

std::vector<float>& GaussianModel::values(GaussianParameter p) {
  return const_cast<std::vector<float>&>(static_cast<const GaussianModel*>(this)->values(p));
}

const std::vector<float>& GaussianModel::values(GaussianParameter p) const {
  switch (p) {
    case kParamPositions:
      return positions;
    case kParamLogScales:
      return log_scales;
    case kParamRotations:
      return rotations;
    case kParamOpacityLogits:
      return opacity_logits;
    default:
      return sh;
  }
}

void GaussianModel::Resize(size_t n) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    values(param).resize(n * static_cast<size_t>(width(param)));
  }
}

void GaussianModel::AppendCopies(const std::vector<uint32_t>& rows) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    AppendRowCopies(rows, static_cast<size_t>(width(param)), &values(param));
  }
}

void GaussianModel::Append(const GaussianModel& other) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    const std::vector<float>& from = other.values(param);
    values(param).insert(values(param).end(), from.begin(), from.end());
  }
}

void GaussianModel::Keep(const std::vector<uint8_t>& keep) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    KeepRows(keep, static_cast<size_t>(width(param)), &values(param));
  }
}

void QuaternionMatrix(const float* q, float r[9]) {
  const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (norm == 0) {
    const float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::copy_n(identity, 9, r);
    return;
  }
  const float inv = 1.0f / norm;
  const float w = q[0] * inv, x = q[1] * inv, y = q[2] * inv, z = q[3] * inv;
  r[0] = 1 - 2 * (y * y + z * z), r[1] = 2 * (x * y - w * z), r[2] = 2 * (x * z + w * y);
  r[3] = 2 * (x * y + w * z), r[4] = 1 - 2 * (x * x + z * z), r[5] = 2 * (y * z - w * x);
  r[6] = 2 * (x * z - w * y), r[7] = 2 * (y * z + w * x), r[8] = 1 - 2 * (x * x + y * y);
}

M4dGaussians GaussianView(const GaussianModel& model) {
  M4dGaussians v = {};
  v.count = static_cast<uint32_t>(model.size());
  v.sh_degree = static_cast<uint32_t>(model.sh_degree);
  v.sh_coefficients = static_cast<uint32_t>(ShCoefficients(model.sh_degree));
  v.positions = model.positions.data();
  v.log_scales = model.log_scales.data();
  v.rotations = model.rotations.data();
  v.opacity_logits = model.opacity_logits.data();
  v.sh = model.sh.data();
  return v;
}

LayerGradients GradientView(GaussianModel* gradients) {
  LayerGradients g;
  g.positions = gradients->positions.data();
  g.log_scales = gradients->log_scales.data();
  g.rotations = gradients->rotations.data();
  g.opacity_logits = gradients->opacity_logits.data();
  g.sh = gradients->sh.data();
  return g;
}

namespace {

// Copies SH rows between layouts of different degrees: the first min(from, to) floats of
// each row, zeros after.
void CopyShRows(const float* from, int from_floats, size_t n, int to_floats, float* to) {
  const int common = std::min(from_floats, to_floats);
  for (size_t i = 0; i < n; ++i) {
    std::copy_n(from + i * from_floats, common, to + i * to_floats);
    std::fill(to + i * to_floats + common, to + (i + 1) * to_floats, 0.0f);
  }
}

Status CheckDegree(int sh_degree, const char* what) {
  if (sh_degree < 0 || sh_degree > 3) {
    return Status(M4D_ERR_INVALID_ARG,
                  std::string(what) + ": SH degree " + std::to_string(sh_degree) + " not in 0..3");
  }
  return Status::Ok();
}

}  // namespace

Status ModelFromGaussianSet(const GaussianSet& set, int sh_degree, GaussianModel* model) {
  M4D_RETURN_IF_ERROR(CheckDegree(sh_degree, "model from Gaussian set"));
  M4D_RETURN_IF_ERROR(CheckDegree(set.sh_degree, "model from Gaussian set"));
  const size_t n = set.size();
  if (set.positions.size() != 3 * n || set.log_scales.size() != 3 * n ||
      set.rotations.size() != 4 * n || set.sh.size() != n * set.sh_floats()) {
    return Status(M4D_ERR_INVALID_ARG, "model from Gaussian set: inconsistent array sizes");
  }
  model->sh_degree = sh_degree;
  model->positions.assign(set.positions.begin(), set.positions.end());
  model->log_scales.assign(set.log_scales.begin(), set.log_scales.end());
  model->rotations.assign(set.rotations.begin(), set.rotations.end());
  model->opacity_logits.assign(set.opacity_logits.begin(), set.opacity_logits.end());
  model->sh.resize(n * model->sh_floats());
  CopyShRows(set.sh.data(), set.sh_floats(), n, model->sh_floats(), model->sh.data());
  return Status::Ok();
}

Status ModelToGaussianSet(const GaussianModel& model, int sh_degree, GaussianSet* set) {
  M4D_RETURN_IF_ERROR(CheckDegree(sh_degree, "model to Gaussian set"));
  if (sh_degree > model.sh_degree) {
    return Status(M4D_ERR_INVALID_ARG, "model to Gaussian set: SH degree above the model's");
  }
  const size_t n = model.size();
  set->sh_degree = sh_degree;
  set->Resize(n);
  std::copy(model.positions.begin(), model.positions.end(), set->positions.begin());
  std::copy(model.log_scales.begin(), model.log_scales.end(), set->log_scales.begin());
  std::copy(model.rotations.begin(), model.rotations.end(), set->rotations.begin());
  std::copy(model.opacity_logits.begin(), model.opacity_logits.end(), set->opacity_logits.begin());
  CopyShRows(model.sh.data(), model.sh_floats(), n, set->sh_floats(), set->sh.data());
  return Status::Ok();
}

}  // namespace m4d
