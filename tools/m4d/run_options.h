// The command-line options of an encode run's arguments (encoder/src/run/), shared by the
// m4d commands that take them.
#ifndef M4D_TOOLS_M4D_RUN_OPTIONS_H_
#define M4D_TOOLS_M4D_RUN_OPTIONS_H_

#include <CLI/CLI.hpp>
#include <string>

#include "encoder/src/run/capture_arguments.h"
#include "encoder/src/run/prune_share_arguments.h"
#include "encoder/src/run/rate_weight_arguments.h"
#include "encoder/src/run/rd_sweep.h"

namespace m4d {

// Adds DATASET and the loading options to a command.
void AddCaptureArguments(CLI::App* command, CaptureArguments* args);

// Adds the three options to a command (`what` says which trainings the prune share applies to).
void AddPruneShareOptions(CLI::App* command, const char* what, PruneShareArguments* args);

// Adds --keyframe-rate-weight to a command.
void AddRateWeightOption(CLI::App* command, RateWeightArguments* args);

// Adds --strategy to `command`; an empty `name` keeps the schedule's.
void AddStrategyOption(CLI::App* command, std::string* name);

// -o,--output-dir and --reuse.
void AddSweepOutputOptions(CLI::App* command, SweepOutput* out);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_RUN_OPTIONS_H_
