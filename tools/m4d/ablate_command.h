// m4d ablate: the paper's ablation study (section 5.3). The full method and each ablation (no
// decoupling, no motion estimation, no compensation, a fixed GOP, no rate term) are swept over
// lambda_2 from one shared first keyframe; the table gives each one's rate and quality and
// its Bjontegaard deltas against the full method, also as ablate.json and an RD plot.
#ifndef M4D_TOOLS_M4D_ABLATE_COMMAND_H_
#define M4D_TOOLS_M4D_ABLATE_COMMAND_H_

#include <CLI/CLI.hpp>

namespace m4d {

void AddAblateCommand(CLI::App* app, int* exit_code);

}  // namespace m4d

#endif  // M4D_TOOLS_M4D_ABLATE_COMMAND_H_
