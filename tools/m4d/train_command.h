// m4d train: trains one frame's 3DGS model (the keyframe stage, a training run of
// speed, and writes the model as a 3DGS PLY.
#ifndef M4D_TOOLS_M4D_TRAIN_COMMAND_H_
#define M4D_TOOLS_M4D_TRAIN_COMMAND_H_

#include <CLI/CLI.hpp>

namespace m4d {

// Registers the subcommand; its callback runs it and sets *exit_code.
void AddTrainCommand(CLI::App* app, int* exit_code);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_TRAIN_COMMAND_H_
