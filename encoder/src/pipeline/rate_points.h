// Rate points: the encoder settings that trade bytes for quality, r1 (fewest bytes) to r5.
// The paper sweeps the motion grid's rate weight lambda_2 alone. With compensation coded on
// every frame the grid is a few hundred bytes of an inter frame and the compensated Gaussians
// are most of the rest, and a coarser grid (larger lambda_2) leaves more for compensation to
// add: alone, a larger lambda_2 spends more bytes (the encoder now codes compensation only
// where it pays, EncoderOptions::compensation_min_gain). So each rate point pairs the paper's
// lambda_2 with the replication threshold tau_g of compensation (how many Gaussians it adds:
// lambda_3 prunes few of them in compensation's 60 steps, see compensation_training.h) and
// bit depths for the compensated Gaussians and the keyframes.
#ifndef M4D_ENCODER_PIPELINE_RATE_POINTS_H_
#define M4D_ENCODER_PIPELINE_RATE_POINTS_H_

#include <string>
#include <vector>

#include "encoder/src/pipeline/encoder_options.h"
#include "encoder/src/train/keyframe_bits_selection.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct RatePointSettings {
  std::string name;                   // "r1" .. "r5"
  double motion_rate_weight = 0;      // lambda_2
  float replication_gradient = 0;     // tau_g
  GaussianQuantization keyframe;      // both keyframe layers
  double keyframe_rate_weight = 0;    // lambda_k of keyframe training
  GaussianQuantization compensation;  // the compensated Gaussians of inter frames
};

// r1 .. r5, fewest bytes first; lambda_2 = 5e-4, 3e-4, 2e-4, 1e-4, 5e-5 (the paper's set).
const std::vector<RatePointSettings>& RatePoints();

// The rate point called `name`.
Status FindRatePoint(const std::string& name, RatePointSettings* point);

// The rate point whose lambda_2 is nearest lambda_2 (on a log scale), with lambda_2 itself:
// how an arbitrary lambda_2 gets the other settings.
RatePointSettings RatePointForLambda(double lambda_2);

// Sets the options that the rate point steers.
void ApplyRatePoint(const RatePointSettings& point, EncoderOptions* options);

// The keyframe quantizations the keyframe bits selection offers at rate point `name`: the
// point's own, then each coarser point's, finest first (empty for an unknown name).
std::vector<KeyframeBitsCandidate> KeyframeBitsCandidates(const std::string& name);

// "p/s/r/o/c/sh": the bit depths of a quantization.
std::string QuantizationName(const GaussianQuantization& q);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_RATE_POINTS_H_
