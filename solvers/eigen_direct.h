// Eigen's sparse direct solvers behind the LinearSolver life cycle:
//   eigen-ldlt  SimplicialLDLT, AMD ordering (the always-available default)
//   eigen-llt   SimplicialLLT,  AMD ordering
//   eigen-lu    SparseLU,       COLAMD ordering (also solves indefinite, non-singular systems)
// Based on: T. A. Davis, Direct Methods for Sparse Linear Systems, SIAM (2006); Eigen's Sparse module.
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

std::unique_ptr<LinearSolver> make_eigen_ldlt(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_eigen_llt(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_eigen_lu(const SolverOptions& options);

}  // namespace coons::solvers
