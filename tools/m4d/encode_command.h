// m4d encode: codes a dataset into an M4D stream with the reference encoder (an encode run,
// encoder/src/run/encode_run.h) and reports bytes, quality and time per frame.
#ifndef M4D_TOOLS_M4D_ENCODE_COMMAND_H_
#define M4D_TOOLS_M4D_ENCODE_COMMAND_H_

#include <CLI/CLI.hpp>

#include "encoder/src/run/encode_run.h"

namespace m4d {

// Adds the encoder's options (stages, GOP, ablations, rate) to a command.
void AddEncoderOptions(CLI::App* command, EncodeArguments* args);

void AddEncodeCommand(CLI::App* app, int* exit_code);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_ENCODE_COMMAND_H_
