// SuiteSparse's direct solvers behind the LinearSolver life cycle, through their C interfaces
// (so that orderings, factor statistics and statuses are all visible):
//   cholmod             supernodal LLᵀ (BLAS-3 on supernodes; OpenBLAS when installed)
//   cholmod-simplicial  simplicial LDLᵀ (up-looking, no BLAS)
//   umfpack             unsymmetric-pattern multifrontal LU (also indefinite, non-singular systems)
// Ordering (SolverOptions::ordering): auto = AMD for CHOLMOD, which is faster here than CHOLMOD's
// default METIS-or-AMD search at every size measured (docs/solvers.md; the benchmark shows both);
// metis, nested-dissection (CHOLMOD's NESDIS), natural and amd can be asked for.
// Based on: T. A. Davis et al., Algorithm 887: CHOLMOD, ACM TOMS 35 (2008); T. A. Davis,
// Algorithm 832: UMFPACK V4.3, ACM TOMS 30 (2004).
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

std::unique_ptr<LinearSolver> make_cholmod_supernodal(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_cholmod_simplicial(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_umfpack(const SolverOptions& options);

}  // namespace coons::solvers
