#include "encoder/src/train/densification_strategy.h"

namespace m4d {

const char* StrategyName(DensificationStrategyKind kind) {
  return kind == DensificationStrategyKind::kMcmc ? "mcmc" : "adc";
}

bool ParseStrategyName(const std::string& name, DensificationStrategyKind* kind) {
  if (name == "adc") {
    *kind = DensificationStrategyKind::kAdaptiveDensityControl;
  } else if (name == "mcmc") {
    *kind = DensificationStrategyKind::kMcmc;
  } else {
    return false;
  }
  return true;
}

}  // namespace m4d
