// The α search on a B-spline boundary (docs/math.md §10): the non-uniform mask family, each α one
// factorisation and two solves (the net N and dN/dα, nonuniform_mask.h; outside [−1/4, 0] first
// those of the near-singular estimate, near_singular.h, all counted in `solves`), the objective's exact
// value and derivative from the B-spline energies (bspline_energy.h) and the discrete energies of
// the net. A coarse scan over the bounds, then the root of the derivative inside the bracket of
// the best scan point (Illinois regula falsi, bisection safeguard). Flat objectives, optima on a
// bound and failed evaluations next to the optimum are reported as such (the statuses of
// alpha_search.h). Evaluated on the boundary moved to its centre (bspline_centre, bspline_net.h).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) (the α search).
#pragma once

#include <optional>
#include <string>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/surfaces/bspline_surface.h"
#include "solvers/linear_solver.h"

namespace coons {

//! The objective's value and dvalue/dα at α, or nullopt when the solve failed (`status` then
//! holds why); `solves` gets the linear solves made (NonUniformSolveResult::solves).
struct BSplineObjectiveValue {
  double value = 0, derivative = 0;
};
std::optional<BSplineObjectiveValue> bspline_alpha_objective(const BSplineBoundary& compatible,
                                                             const Objective& objective, double alpha,
                                                             solvers::LinearSolver& solver,
                                                             solvers::SolveStatus* status = nullptr,
                                                             int* solves = nullptr);

//! Objectives the B-spline search takes: energies and discrete energies (a target term is not:
//! the targets compare Bézier nets). False with the reason in *why otherwise.
bool bspline_objective_supported(const Objective& objective, std::string* why);

//! The default bounds of the B-spline search: [−1/4, 0], where the non-uniform system is positive
//! definite (docs/math.md §10); above 0 it can be singular on strongly non-uniform abscissae.
//! Flat below a relative range of 1e-9 (the energies' rounding on short knot spans is ~1e-11).
AlphaSearchOptions default_bspline_search_options();

//! The largest α in [0, 1/4] up to which the non-uniform system of `compatible` is positive
//! definite with min|λ|/max|λ| above 10 × kNearSingularEigenvalueRatio: 1/4 when α = 1/4 passes
//! (Cholesky and the eigenvalue-ratio estimate), else bisection on [0, 1/4] to 1e−6 of it (the
//! definite α form an interval holding [−1/4, 0]: the system is affine in α).
double bspline_definite_upper(const BSplineBoundary& compatible);

//! The bounds `search-alpha` and the study search a B-spline boundary over by default:
//! default_bspline_search_options() up to bspline_definite_upper(compatible), the contract's
//! [−1/4, 1/4] wherever the system is definite there.
AlphaSearchOptions bspline_search_options(const BSplineBoundary& compatible);

//! A note for a search whose optimum lies within 2 % of the bounds' width below `definite_upper`,
//! the upper bound, where that end was cut short of 1/4 by a singular α: the objective rises there
//! because of the singular α (bspline_wave's Dirichlet energy falls across [0, 0.1149] and has its
//! "minimum" 0.0015 below the singular end 0.1164). Empty otherwise.
std::string bspline_pole_note(const AlphaSearchSummary& s, const AlphaSearchOptions& options, double definite_upper);

//! The search; `solver_name` a backend of the registry that takes an assembled matrix. Outside
//! [−1/4, 0] an α whose system is near-singular (near_singular.h) is a failed evaluation, status
//! singular (bspline_alpha_objective gives nullopt there).
AlphaSearchSummary search_bspline_alpha(const BSplineBoundary& compatible, const Objective& objective,
                                        const std::string& solver_name,
                                        const AlphaSearchOptions& options = default_bspline_search_options(),
                                        const solvers::SolverOptions& solver_options = {});

}  // namespace coons
