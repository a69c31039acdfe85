// m4d bench: what the codec costs in time, in one command: the reference encoder's time per
// frame by stage (keyframe training, decoupling, motion estimation, compensation, coding with
// its closed-loop decode, evaluation) and the SDK's decode time per frame.
#ifndef M4D_TOOLS_M4D_BENCH_COMMAND_H_
#define M4D_TOOLS_M4D_BENCH_COMMAND_H_

#include <CLI/CLI.hpp>

namespace m4d {

void AddBenchCommand(CLI::App* app, int* exit_code);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_BENCH_COMMAND_H_
