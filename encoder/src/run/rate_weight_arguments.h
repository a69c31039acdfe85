// --keyframe-rate-weight, shared by m4d train and encode: lambda_k of the first keyframe's rate
// term, given, the rate point's, or chosen per capture (rate_weight_selection.h).
#ifndef M4D_ENCODER_RUN_RATE_WEIGHT_ARGUMENTS_H_
#define M4D_ENCODER_RUN_RATE_WEIGHT_ARGUMENTS_H_

#include <nlohmann/json.hpp>

#include "encoder/src/capture/capture.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/prune_share_selection.h"
#include "encoder/src/train/rate_weight_selection.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct RateWeightArguments {
  double weight = -1;      // < 0: the rate point's
  bool automatic = false;  // "auto": chosen per capture
  double max_loss_per_halving_db = PruneShareSelectionOptions().max_loss_per_halving_db;
};

// The weight for a keyframe of `frame` trained with `options` (its prune share already
// resolved): the given one, `fallback` (the rate point's), or the selection's (progress on
// stderr, its table on stdout; `choice` holds its trials).
Status ResolveRateWeight(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                         const RateWeightArguments& args, double fallback, double* weight,
                         RateWeightChoice* choice);

// What a report records of the selection (null when the weight was not chosen per capture).
nlohmann::json RateWeightJson(const RateWeightArguments& args, const RateWeightChoice& choice);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_RATE_WEIGHT_ARGUMENTS_H_
