// m4d: the reference encoder's command line. Subcommands: scene (write the built-in
// synthetic scene), train (one frame's 3D Gaussians), encode (a multi-view video to a stream),
// rd (an RD sweep over lambda_2 against the baselines), ablate (the paper's ablation study),
// bench (encode and decode time per frame). Under mpirun or srun, encode spreads chunks of
// the frames over the ranks (chunked_encode.h).
#include <CLI/CLI.hpp>
#include <cstdio>

#include "encoder/src/distributed/mpi_ranks.h"
#include "m4d/m4d.h"
#include "tools/m4d/ablate_command.h"
#include "tools/m4d/bench_command.h"
#include "tools/m4d/encode_command.h"
#include "tools/m4d/rd_command.h"
#include "tools/m4d/scene_command.h"
#include "tools/m4d/train_command.h"
#include "tools/usage_exit.h"

int main(int argc, char** argv) {
  // Tables on stdout and progress on stderr interleave in order even when both go to a file.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CLI::App app{"m4d: motion-decoupled 4D Gaussian video codec, reference encoder"};
  app.require_subcommand(1);
  int exit_code = 0;
  const m4d::Status ranks = m4d::StartRanks(&argc, &argv);
  if (!ranks.ok()) {
    std::fprintf(stderr, "m4d: %s\n", ranks.message().c_str());
    return 2;
  }
  m4d::AddSceneCommand(&app, &exit_code);
  m4d::AddTrainCommand(&app, &exit_code);
  m4d::AddEncodeCommand(&app, &exit_code);
  m4d::AddRdCommand(&app, &exit_code);
  m4d::AddAblateCommand(&app, &exit_code);
  m4d::AddBenchCommand(&app, &exit_code);
  M4D_PARSE_ARGUMENTS(app, argc, argv);
  m4d::FinishRanks(exit_code);
  return exit_code;
}
