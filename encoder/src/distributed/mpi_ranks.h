// The processes of a distributed encoding: under an MPI launcher (mpirun, Slurm's srun) each
// process is one rank of the job; run plainly, m4d is the only rank. MPI is initialised only
// when a launcher started the process, so the single-process path never needs it.
#ifndef M4D_ENCODER_DISTRIBUTED_MPI_RANKS_H_
#define M4D_ENCODER_DISTRIBUTED_MPI_RANKS_H_

#include <string>

#include "sdk/src/common/status.h"

namespace m4d {

struct Ranks {
  int rank = 0;
  int size = 1;
};

// Joins the MPI job when a launcher started this process (and m4d was built with MPI); fails
// when a launcher started several ranks of a build without MPI.
Status StartRanks(int* argc, char*** argv);
const Ranks& CurrentRanks();
// Leaves the MPI job (when joined); call once, at exit. A failed rank (exit_code non-zero)
// aborts the job, so that no other rank waits for it.
void FinishRanks(int exit_code);

// Collective: whether every rank's `ok` is true.
bool AllRanksOk(bool ok);
// Collective: rank 0's values on every rank.
void BroadcastDoubles(double* values, int count);

// "rank r: " under a launcher of several ranks, else "".
std::string RankPrefix();

}  // namespace m4d

#endif  // M4D_ENCODER_DISTRIBUTED_MPI_RANKS_H_
