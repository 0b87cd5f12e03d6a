// Solving the triangular mask system (tri_mask.h) of a boundary with a backend of the solver
// registry. The system is not symmetric unless c = 0, so only backends for general matrices apply
// (eigen-lu, umfpack, bicgstab, and gmres, a grid-stencil backend that also takes an assembled
// matrix: asked of the backend, not listed here); Cholesky-type and CG backends (registry flag
// definite_only) apply only to c = 0, where A = I − (1/6)·(interior adjacency) is symmetric positive
// definite; the other grid-stencil backends (jacobi, gauss-seidel, dst, fast, mg) know only
// rectangular grids. A backend that does not apply reports not_applicable and leaves the interior
// untouched.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <string>
#include <vector>

#include "coons/tri/tri_mask.h"
#include "coons/tri/tri_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons::tri {

//! Whether a registry backend may solve the triangular system of `mask`, and if not, why.
struct TriBackendCheck {
  bool applicable = false;
  std::string reason;  //!< empty when applicable
};
TriBackendCheck check_tri_backend(const solvers::SolverInfo& solver, const TriMask& mask);

//! The backend `auto` stands for on triangular systems: an LU-type one (umfpack when it is built,
//! else eigen-lu), which applies to every member of the family.
const solvers::SolverInfo& default_tri_solver();

//! The registry backends (in registry order) that apply to the system of `mask`.
std::vector<std::string> tri_applicable_solvers(const TriMask& mask);

struct TriSolveOptions {
  TriMask mask;  //!< the member of the family (its c)
  //! A backend of the registry (never null; names become backends only in the CLI).
  const solvers::SolverInfo* solver = &default_tri_solver();
  solvers::SolverOptions solver_options;  //!< tolerance, ordering, ...

  //! True when the mask and the solver options are usable and a solver is set; else why.
  bool is_valid(std::string* why) const;
};

struct TriSolveResult {
  TriNet net;                     //!< the boundary with the solved interior (frame only on failure)
  solvers::SolveSummary summary;  //!< status kNotApplicable for a backend that does not apply
};

//! Whether c lies in (c*ₙ, 1/3] (any c for n < 4), where no member of degree n is singular
//! (checked for n = 4 … 20 in the tests, and to 40 by the generalised eigenvalues of the pencil).
//! Outside it lie further singular members, for every boundary: c = 2/3 at n = 6, c = 1 at n = 8,
//! c ≈ −0.62 at n = 10, and one just above 1/3 and one just below c*ₙ for every larger n.
bool in_regular_c_range(int n, const TriMask& mask);

//! Factorise sys.A with `solver` and solve A X = B (X: #interior by 3). The factorisation is
//! first checked by inverse iteration (coons/mask/near_singular.h): a system whose min|λ|/‖A‖₁ is
//! at most kNearSingularEigenvalueRatio is refused with status singular and X = 0, because on
//! boundary data that the singular system can still reproduce (a flat triangle) every backend
//! returns one of many nets with a small residual and calls it a success. Inside
//! in_regular_c_range too: just above c*ₙ the system is as near singular as just below it.
solvers::SolveSummary solve_tri_system(const TriMaskSystem& sys, solvers::LinearSolver& solver, Eigen::MatrixX3d& X);

//! Fill the interior of `frame` (its interior is ignored) by the mask system.
TriSolveResult solve_tri_net(const TriNet& frame, const TriSolveOptions& options = {});
//! The same from the three sides (frame_net(boundary)).
TriSolveResult solve_tri_net(const TriBoundary& boundary, const TriSolveOptions& options = {});

}  // namespace coons::tri
