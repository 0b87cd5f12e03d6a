// The one place where backend names become solver objects (cf. Ceres's SparseCholesky::Create).
// The CLI, the tests and the benchmarks all iterate over available_solvers().
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "linear_solver.h"

namespace coons::solvers {

enum class SolverFamily { kDirect, kIterative, kStructured };
const char* to_string(SolverFamily family);

struct SolverInfo {
  std::string name;
  SolverFamily family;
  bool needs_matrix;        //!< works from the assembled matrix (else from the grid stencil)
  bool definite_only;       //!< only for positive definite operators (Cholesky-type)
  bool uses_threads;        //!< uses SolverOptions::threads (FFTW threads or OpenMP); else one thread
  std::string description;  //!< one line for `coons solvers`
};

//! Every backend built into this binary, in a fixed order.
const std::vector<SolverInfo>& available_solvers();

//! Info of a backend, or nullptr when no backend of that name was built.
const SolverInfo* find_solver(std::string_view name);

//! Whether the backend solves an operator given only as an assembled matrix: every needs_matrix
//! backend, and the grid-stencil ones that fall back to the matrix (gmres, with ILUT). Asked of the
//! backend itself (analyze on a 1×1 matrix), so that no list of names is kept.
bool accepts_matrix(const SolverInfo& info);

//! SolverInfo::uses_threads of the backend of that name (false for a name not built): dst, fast,
//! fast5, separable-banded, mg, mg-cg and gmres on its multigrid path use the threads.
bool uses_threads(std::string_view name);

//! The sparse direct backend of an assembled matrix where no structure is used: cholmod (when
//! built, else eigen-ldlt) for a definite system, eigen-lu otherwise.
const SolverInfo& default_matrix_solver(bool definite);

//! The backend that `auto` stands for on this operator: the fastest applicable one built in.
std::string choose_auto_solver(const GridStencil& stencil);

//! A new backend of that name, or nullptr when there is none.
std::unique_ptr<LinearSolver> make_solver(std::string_view name, const SolverOptions& options = {});

}  // namespace coons::solvers
