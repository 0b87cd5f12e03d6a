// coons — discrete Coons patches from the command line. See README.md and docs/formats.md.
#include <glog/logging.h>

#include <iostream>
#include <string_view>

#include "registry.h"
#include "solvers/mpi_runtime.h"

// Under mpirun/srun every rank runs the same command; the session starts MPI for the distributed
// backends (hypre) and silences every rank but 0. Without a launcher it does nothing. Only `solve`
// is distributed: another command on several ranks would write its files once per rank.
int main(int argc, char** argv) {
  // Ceres logs through glog: its warnings ("Trying to extract roots from a constant polynomial"
  // inside a line search) reached standard error of a successful search. Every outcome they could
  // matter to is in Ceres's summary, which the searches read and report; only fatal ones are kept.
  google::InitGoogleLogging(argv[0]);
  FLAGS_minloglevel = google::GLOG_FATAL;
  const coons::solvers::MpiSession mpi;
  if (coons::solvers::mpi_size() > 1 && (argc < 2 || std::string_view(argv[1]) != "solve")) {
    std::cerr << "error: command line: only `coons solve` runs on several MPI ranks (" << coons::solvers::mpi_size()
              << " given)\n";
    return 2;
  }
  return coons::cli::run(argc, argv);
}
