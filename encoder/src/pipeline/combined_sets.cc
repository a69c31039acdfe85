#include "encoder/src/pipeline/combined_sets.h"

#include <algorithm>

namespace m4d {

void AppendKept(const GaussianSet& from, const std::vector<uint8_t>* removed, GaussianSet* to) {
  const size_t k = static_cast<size_t>(from.sh_floats());
  for (size_t i = 0; i < from.size(); ++i) {
    if (removed && (*removed)[i]) continue;
    const size_t j = to->size();
    to->Resize(j + 1);
    std::copy_n(&from.positions[3 * i], 3, &to->positions[3 * j]);
    std::copy_n(&from.log_scales[3 * i], 3, &to->log_scales[3 * j]);
    std::copy_n(&from.rotations[4 * i], 4, &to->rotations[4 * j]);
    to->opacity_logits[j] = from.opacity_logits[i];
    std::copy_n(&from.sh[k * i], k, &to->sh[k * j]);
  }
}

Status CombinedModel(const GaussianSet& static_set, const GaussianSet& dynamic_set,
                     GaussianModel* model) {
  GaussianModel other;
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(static_set, static_set.sh_degree, model));
  M4D_RETURN_IF_ERROR(ModelFromGaussianSet(dynamic_set, static_set.sh_degree, &other));
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    std::vector<float>& to = model->values(param);
    const std::vector<float>& from = other.values(param);
    to.insert(to.end(), from.begin(), from.end());
  }
  return Status::Ok();
}

}  // namespace m4d
