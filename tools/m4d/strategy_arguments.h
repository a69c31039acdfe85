// The --strategy option of the commands that train keyframes (densification_strategy.h).
#ifndef M4D_TOOLS_M4D_STRATEGY_ARGUMENTS_H_
#define M4D_TOOLS_M4D_STRATEGY_ARGUMENTS_H_

#include <string>

#include <CLI/CLI.hpp>

#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"

namespace m4d {

// Adds --strategy to `command`; an empty `name` keeps the schedule's.
void AddStrategyOption(CLI::App* command, std::string* name);

// Sets options->strategy from a name AddStrategyOption accepted (empty: unchanged).
void ApplyStrategy(const std::string& name, KeyframeTrainingOptions* options);

// Prints the starts tried and, per tenth of the run, the Gaussians and the loss.
void PrintTrainingReport(const KeyframeTrainingReport& report);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_STRATEGY_ARGUMENTS_H_
