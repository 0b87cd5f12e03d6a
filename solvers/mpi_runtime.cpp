#include "mpi_runtime.h"

#include <cstdio>
#include <cstdlib>

#include "coons/config.h"
#if COONS_HAVE_MPI
#include <mpi.h>
#endif
#if COONS_HAVE_HYPRE
#include <HYPRE_utilities.h>
#endif

namespace coons::solvers {

namespace {

#if COONS_HAVE_MPI
bool started_here = false;  // MPI_Init was ours, so MPI_Finalize is ours too

void finalize_mpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized || !started_here) return;
#if COONS_HAVE_HYPRE
  HYPRE_Finalize();
#endif
  MPI_Finalize();
}
#endif

}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "SLURM_STEP_NUM_TASKS"})
    if (std::getenv(name)) return true;
  return false;
}

bool ensure_mpi() {
#if COONS_HAVE_MPI
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) return true;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  started_here = true;
#if COONS_HAVE_HYPRE
  HYPRE_Init();
#endif
  std::atexit(finalize_mpi);
  return true;
#else
  return false;
#endif
}

int mpi_rank() {
#if COONS_HAVE_MPI
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) return 0;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
#else
  return 0;
#endif
}

int mpi_size() {
#if COONS_HAVE_MPI
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) return 1;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
#else
  return 1;
#endif
}

std::pair<long long, long long> block_of(long long n, int rank, int size) {
  const long long base = n / size;
  const long long extra = n % size;
  const long long first = rank * base + (rank < extra ? rank : extra);
  return {first, first + base + (rank < extra ? 1 : 0)};
}

MpiSession::MpiSession() {
  if (!launched_by_mpi() || !ensure_mpi()) return;
  if (mpi_rank() != 0) {  // rank 0 alone speaks
    if (!std::freopen("/dev/null", "w", stdout)) std::fclose(stdout);
    if (!std::freopen("/dev/null", "w", stderr)) std::fclose(stderr);
  }
}

MpiSession::~MpiSession() {
#if COONS_HAVE_MPI
  finalize_mpi();
#endif
}

}  // namespace coons::solvers
