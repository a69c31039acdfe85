#include "encoder/src/decoupling/motion_classification.h"

namespace m4d {

std::vector<uint8_t> ClassifyDynamic(const LookaheadMeasures& measures,
                                     const DecouplingThresholds& thresholds,
                                     const std::vector<uint32_t>& neighbours) {
  const size_t n = measures.size();
  std::vector<uint8_t> refined(n, 0);
  const bool supported = measures.change_support.size() == n;
  for (size_t i = 0; i < n; ++i) {
    const bool moved = (measures.displacement[i] > thresholds.displacement ||
                        measures.scale_change[i] > thresholds.scale_change) &&
                       (!supported || measures.change_support[i] >= thresholds.change_support);
    const bool artefact = measures.error[i] > thresholds.error;  // false for NaN
    refined[i] = moved && !artefact ? 1 : 0;
  }
  const size_t k = static_cast<size_t>(thresholds.neighbours);
  if (k == 0 || neighbours.size() != n * k) return refined;
  std::vector<uint8_t> voted(n);
  for (size_t i = 0; i < n; ++i) {
    size_t dynamic_votes = refined[i], voters = 1;
    for (size_t j = 0; j < k; ++j) {
      const uint32_t other = neighbours[i * k + j];
      if (other >= n) continue;  // an empty slot (fewer Gaussians than K)
      dynamic_votes += refined[other];
      ++voters;
    }
    voted[i] = 2 * dynamic_votes > voters ? 1 : 0;
  }
  return voted;
}

}  // namespace m4d
