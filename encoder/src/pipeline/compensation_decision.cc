#include "encoder/src/pipeline/compensation_decision.h"

#include <algorithm>

#include "encoder/src/pipeline/combined_sets.h"

namespace m4d {

void ClearCompensation(size_t moved_size, int sh_degree, CompensationResult* compensation) {
  compensation->removed.assign(moved_size, 0);
  compensation->added = GaussianSet();
  compensation->added.sh_degree = sh_degree;
}

Status CompensationGain(const GaussianSet& moved, const GaussianSet& kept, const GaussianSet& added,
                        TrainingPsnrMeter* meter, double* gain) {
  GaussianSet coded;
  coded.sh_degree = moved.sh_degree;
  AppendKept(kept, nullptr, &coded);
  AppendKept(added, nullptr, &coded);
  double with = 0, without = 0;
  M4D_RETURN_IF_ERROR(meter->Measure(coded, &with));
  M4D_RETURN_IF_ERROR(meter->Measure(moved, &without));
  *gain = with - without;
  return Status::Ok();
}

Status DecideCompensation(const GaussianSet& moved, double min_gain, int sh_degree,
                          TrainingPsnrMeter* meter, CompensationResult* compensation,
                          CompensationDecision* decision) {
  decision->gain = compensation->abandoned ? compensation->probed_gain : 0.0;
  GaussianSet coded;  // the frame with its compensation, before the compensation's quantization
  coded.sh_degree = moved.sh_degree;
  AppendKept(moved, &compensation->removed, &coded);
  AppendKept(compensation->added, nullptr, &coded);
  M4D_RETURN_IF_ERROR(meter->Measure(coded, &decision->training_psnr));
  if (compensation->added.size() == 0 &&
      std::count(compensation->removed.begin(), compensation->removed.end(), 1) == 0) {
    return Status::Ok();
  }
  double without = 0;
  M4D_RETURN_IF_ERROR(meter->Measure(moved, &without));
  decision->gain = decision->training_psnr - without;
  if (decision->gain >= min_gain) return Status::Ok();
  ClearCompensation(moved.size(), sh_degree, compensation);
  decision->training_psnr = without;
  return Status::Ok();
}

}  // namespace m4d
