// The compensation mode decision: an inter frame codes its trained compensation only if that
// raises the training views' mean PSNR by at least EncoderOptions::compensation_min_gain;
// otherwise its bytes would buy nothing. The same comparison, made on a compensation still in
// training, is the probe of its early decision (CompensationOptions::probe_iteration).
#ifndef M4D_ENCODER_PIPELINE_COMPENSATION_DECISION_H_
#define M4D_ENCODER_PIPELINE_COMPENSATION_DECISION_H_

#include <cstddef>

#include "encoder/src/compensation/compensation_training.h"
#include "encoder/src/pipeline/training_psnr_meter.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

struct CompensationDecision {
  double training_psnr = 0;  // of the frame as it will be coded
  // Training PSNR with the compensation minus without it (dB) when it adds or removes
  // Gaussians; else the probe's when the early decision abandoned it; else 0.
  double gain = 0;
};

// A compensation of a dynamic set of `moved_size` Gaussians that adds and removes nothing.
void ClearCompensation(size_t moved_size, int sh_degree, CompensationResult* compensation);

// Training PSNR of `kept` (moved without the removed Gaussians) with `added`, minus moved's: the
// probe of the early decision.
Status CompensationGain(const GaussianSet& moved, const GaussianSet& kept, const GaussianSet& added,
                        TrainingPsnrMeter* meter, double* gain);

// Clears *compensation (ClearCompensation, at sh_degree) when it gains less than min_gain. The
// meter has started the frame.
Status DecideCompensation(const GaussianSet& moved, double min_gain, int sh_degree,
                          TrainingPsnrMeter* meter, CompensationResult* compensation,
                          CompensationDecision* decision);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_COMPENSATION_DECISION_H_
