// The --strategy option of the commands that train keyframes (densification_strategy.h).
#ifndef M4D_ENCODER_RUN_STRATEGY_ARGUMENTS_H_
#define M4D_ENCODER_RUN_STRATEGY_ARGUMENTS_H_

#include <string>

#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"

namespace m4d {

// Sets options->strategy from a name AddStrategyOption accepted (empty: unchanged).
void ApplyStrategy(const std::string& name, KeyframeTrainingOptions* options);

// Prints the starts tried and, per tenth of the run, the Gaussians and the loss.
void PrintTrainingReport(const KeyframeTrainingReport& report);

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_STRATEGY_ARGUMENTS_H_
