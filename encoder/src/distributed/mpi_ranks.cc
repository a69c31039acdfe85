#include "encoder/src/distributed/mpi_ranks.h"

#include <cstdlib>

#ifdef M4D_HAVE_MPI
#include <mpi.h>
#endif

namespace m4d {
namespace {

Ranks g_ranks;
#ifdef M4D_HAVE_MPI
bool g_joined = false;  // MPI_Init succeeded
#endif

// The rank count a launcher announced (Open MPI's mpirun, PMIx as srun --mpi=pmix starts
// it, or PMI): 0 when none started this process.
int LauncherSize() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"}) {
    if (const char* v = std::getenv(name)) return std::atoi(v);
  }
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

}  // namespace

Status StartRanks(int* argc, char*** argv) {
  const int size = LauncherSize();
  if (size <= 0) return Status::Ok();
#ifdef M4D_HAVE_MPI
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    return Status(M4D_ERR_INVALID_ARG, "MPI: initialisation failed");
  }
  g_joined = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_ranks.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_ranks.size);
  return Status::Ok();
#else
  (void)argc;
  (void)argv;
  if (size == 1) return Status::Ok();
  return Status(M4D_ERR_UNSUPPORTED,
                "started as " + std::to_string(size) +
                    " MPI ranks, but this m4d was built without MPI (install libopenmpi-dev "
                    "and rebuild)");
#endif
}

const Ranks& CurrentRanks() { return g_ranks; }

void FinishRanks(int exit_code) {
#ifdef M4D_HAVE_MPI
  if (g_joined && exit_code != 0 && g_ranks.size > 1) MPI_Abort(MPI_COMM_WORLD, exit_code);
  if (g_joined) MPI_Finalize();
  g_joined = false;
#else
  (void)exit_code;
#endif
}

bool AllRanksOk(bool ok) {
#ifdef M4D_HAVE_MPI
  if (g_joined) {
    int mine = ok ? 1 : 0, all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all == 1;
  }
#endif
  return ok;
}

void BroadcastDoubles(double* values, int count) {
#ifdef M4D_HAVE_MPI
  if (g_joined) MPI_Bcast(values, count, MPI_DOUBLE, 0, MPI_COMM_WORLD);
#else
  (void)values;
  (void)count;
#endif
}

std::string RankPrefix() {
  return g_ranks.size > 1 ? "rank " + std::to_string(g_ranks.rank) + ": " : "";
}

}  // namespace m4d
