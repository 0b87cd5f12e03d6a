// The process-wide MPI state of the distributed backends (the hypre ones). Without MPI in the
// build every function answers for one rank and nothing is initialised.
//
// MPI is started either by an MpiSession at the top of main() (when an MPI launcher — mpirun,
// mpiexec, srun — started the process, so that every rank joins at once) or lazily by the first
// hypre backend (a singleton run: one rank, e.g. the tests). It is finalised once, at exit.
#pragma once

#include <utility>

namespace coons::solvers {

//! True when an MPI launcher started this process (its rank variables are set: Open MPI's
//! OMPI_COMM_WORLD_SIZE, PMI/PMIx's PMI_SIZE or PMIX_RANK, Slurm's srun SLURM_STEP_NUM_TASKS).
bool launched_by_mpi();

//! Initialises MPI (thread level "funneled") and hypre once; false without MPI in the build.
bool ensure_mpi();

//! This process's rank in MPI_COMM_WORLD and the number of ranks (0 and 1 before ensure_mpi()
//! and without MPI).
int mpi_rank();
int mpi_size();

//! The block of n items (rows) that rank `rank` of `size` owns: [first, last). Blocks differ in
//! length by at most one, the longer ones first.
std::pair<long long, long long> block_of(long long n, int rank, int size);

//! For main(): starts MPI when launched by an MPI launcher, and silences standard output and
//! error on every rank but 0 (rank 0 alone prints reports and errors). Finalises at destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

}  // namespace coons::solvers
