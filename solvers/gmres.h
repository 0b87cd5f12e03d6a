// Restarted GMRES(k) with right preconditioning, for nonsymmetric (or indefinite) systems of any
// size n: the operator and the preconditioner are functions y = A x and z = M⁻¹ r on n-vectors.
// Right preconditioning (solve A M⁻¹ u = b, x = M⁻¹ u) keeps the residual GMRES minimises equal to
// the true residual b − A x, so the stopping test is on ‖b − A x‖/‖b‖ itself. Modified Gram–Schmidt
// Arnoldi, Givens rotations; the true residual is recomputed at every restart.
// Preconditioners here: ilut_preconditioner (Eigen's IncompleteLUT on an assembled matrix) and a
// multigrid cycle (Multigrid::precondition).
// Based on: Y. Saad, M. H. Schultz, GMRES: a generalized minimal residual algorithm for solving
// nonsymmetric linear systems, SIAM J. Sci. Stat. Comput. 7 (1986); Y. Saad, Iterative Methods for
// Sparse Linear Systems, 2nd ed., SIAM (2003), §9.3.2.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>

#include "iteration_summary.h"

namespace coons::solvers {

using VectorMap = std::function<void(const Eigen::VectorXd& in, Eigen::VectorXd& out)>;

struct GmresOptions {
  int restart = 50;                                  //!< k: Krylov vectors kept before a restart
  IterationOptions iteration{1e-10, 1000, 1e8, {}};  //!< tolerance and limit on total inner iterations

  bool is_valid(std::string* why) const;
};

//! Solves A x = b from the initial guess x (set to 0 if its size is wrong). precondition may be
//! empty (no preconditioner). iterations counts inner (Arnoldi) steps over all restarts.
IterationSummary gmres(const VectorMap& apply, const VectorMap& precondition, const Eigen::VectorXd& b,
                       Eigen::VectorXd& x, const GmresOptions& options = {});

//! z = (LU)⁻¹ r by Eigen's IncompleteLUT (threshold dropping; computed with compute(), because
//! Eigen 3.4 reads an uninitialised status when analyzePattern and factorize are called apart).
//! Returns an empty map and a message when the factorisation fails.
VectorMap ilut_preconditioner(const Eigen::SparseMatrix<double>& A, std::string* message = nullptr,
                              double drop_tolerance = 1e-4, int fill_factor = 10);

}  // namespace coons::solvers
