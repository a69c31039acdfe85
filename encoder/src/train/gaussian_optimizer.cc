#include "encoder/src/train/gaussian_optimizer.h"

namespace m4d {

AdamOptimizer MakeGaussianOptimizer(const GaussianModel& model, const GaussianLearningRates& rates,
                                    float spatial_scale) {
  AdamOptimizer adam;
  adam.ResizeRows(model.size());
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    adam.AddParameter(model.width(static_cast<GaussianParameter>(p)));
  }
  // A degree-0 model has no higher bands: its f_rest group is empty but keeps its index.
  const int rest = model.sh_floats() - 3;
  adam.AddGroup("xyz", kParamPositions, 0, 3, rates.position.At(0) * spatial_scale);
  adam.AddGroup("f_dc", kParamSh, 0, 3, rates.sh_dc);
  adam.AddGroup("f_rest", kParamSh, 3, rest, rates.sh_rest);
  adam.AddGroup("opacity", kParamOpacityLogits, 0, 1, rates.opacity);
  adam.AddGroup("scaling", kParamLogScales, 0, 3, rates.scaling);
  adam.AddGroup("rotation", kParamRotations, 0, 4, rates.rotation);
  return adam;
}

void StepGaussianOptimizer(const GaussianModel& gradients, GaussianParameter skip,
                           AdamOptimizer* optimizer, GaussianModel* model, ThreadPool* pool) {
  for (int p = 0; p < kGaussianParameterCount; ++p) {
    const auto param = static_cast<GaussianParameter>(p);
    if (param == skip) continue;
    optimizer->Step(p, model->values(param).data(), gradients.values(param).data(), pool);
  }
}

}  // namespace m4d
