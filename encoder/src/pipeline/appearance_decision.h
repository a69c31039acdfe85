// The appearance mode decision: the colour change (APPEARANCE) that motion estimation trained
// with an inter frame's motion is coded only if it raises the mean PSNR of the moved set on the
// training views that did not train it (AppearanceCheckViews), or on all of them when each did,
// by more than its bytes are worth: EncoderOptions::appearance_gain_per_doubling dB per doubling
// of the frame's bytes (docs/design/appearance_update.md). Otherwise its bytes buy too little or
// fit only the views that trained it.
#ifndef M4D_ENCODER_PIPELINE_APPEARANCE_DECISION_H_
#define M4D_ENCODER_PIPELINE_APPEARANCE_DECISION_H_

#include <cstddef>
#include <vector>

#include "encoder/src/pipeline/training_psnr_meter.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/appearance_update.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

struct AppearanceDecision {
  double gain = 0;       // the judging views' PSNR with the change minus without (dB)
  bool skipped = false;  // not above the minimum gain: no APPEARANCE is coded
};

// The gain a colour change of `appearance_bytes` must exceed in a frame whose other payloads
// (the motion grid) take `frame_bytes`: min_gain, raised to gain_per_doubling dB per doubling
// of the frame's bytes it causes. A negative min_gain is no bar at all (always coded).
double RequiredAppearanceGain(double min_gain, double gain_per_doubling, size_t frame_bytes,
                              size_t appearance_bytes);

// Applies `appearance` to *moved unless the decision skips it; measures with the meter, which
// has started the frame, on `check_views` (empty: every view).
Status DecideAppearance(const AppearanceUpdate& appearance, double min_gain,
                        const std::vector<int>& check_views, TrainingPsnrMeter* meter,
                        GaussianSet* moved, AppearanceDecision* decision);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_APPEARANCE_DECISION_H_
