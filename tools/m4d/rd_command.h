// m4d rd: an RD sweep of the reference encoder over lambda_2 (the paper's set by default):
// one stream per rate point, the baselines (every frame coded on its own; every Gaussian
// dynamic) with BD-rate against each, a table, rd.json, and RD curves and per-frame PSNR as PNG.
#ifndef M4D_TOOLS_M4D_RD_COMMAND_H_
#define M4D_TOOLS_M4D_RD_COMMAND_H_

#include <CLI/CLI.hpp>

namespace m4d {

void AddRdCommand(CLI::App* app, int* exit_code);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_RD_COMMAND_H_
