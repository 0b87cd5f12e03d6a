// Searches over a one-parameter stencil family on a stencil problem (stencil_problem.h: any
// number of data rings, any free set):
// - the best weight w of the C1 family (stencil.h: c1_family_stencil, the minimiser
// of w·Σ‖Δ^{2,2}b‖² + (1−w)·(Σ‖Δ^{2,0}b‖² + 2Σ‖Δ^{1,1}b‖² + Σ‖Δ^{0,2}b‖²); w = 1 is c1-coons,
// w = 0 biharmonic) on a stencil problem with two data rings, for an objective of the α search
// (objective.h: thin_plate, twist, dirichlet, e3, ...). It is the α search's run (search_run.h:
// coarse scan, flat and bound verdicts, Ceres's line search on the exact derivative, failed
// evaluations judged) over the evaluator of stencil_family_objective.h (one symbolic analysis, per
// w one factorisation and two solves);
// - the best α of Farin–Hansford's 3×3 family on problems that are not the one-ring rectangle
// (two data rings, a free set with holes or a fixed curve), the same run over the same evaluator
// (search_alpha of alpha_search.h covers the one-ring rectangle, in the sine basis where it can).
// A problem that does not fit the family's stencil (too few data rings, a free point whose stencil
// leaves the net) is refused: SearchStatus::kNotApplicable, nothing evaluated, the message
// "FIELD: reason".
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700; Ceres Solver's
// GradientProblemSolver (S. Agarwal, K. Mierle et al.).
#pragma once

#include <string>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/mask/stencil_problem.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

struct WeightSearchOptions {
  //! The run's settings; bounds [0, 1] (the family's energies are defined there).
  AlphaSearchOptions search{0.0, 1.0};

  //! search.is_valid, and 0 ≤ lower < upper ≤ 1.
  bool is_valid(std::string* why) const;
};

//! w* (summary.parameter), its value, flat / at_bound, evaluations and solves, the scan and the
//! failed evaluations, as search_mask_parameter reports α*; evaluator "factorize and solve".
//! `solver` must work from the matrix (direct or iterative; the 5×5 systems are positive definite).
AlphaSearchSummary search_weight(const StencilProblem& problem, const Objective& objective,
                                 const solvers::SolverInfo& solver, const WeightSearchOptions& options = {},
                                 const solvers::SolverOptions& solver_options = {});

//! α* of the 3×3 family on `problem` (summary.parameter), as search_weight reports w*; bounds from
//! `options` (α ∈ [−1/4, 1/4] keeps every system positive definite; outside it an α whose system
//! is near-singular is a failed evaluation, `singular`: near_singular.h). `solver` must work from
//! the matrix.
AlphaSearchSummary search_alpha_on_problem(const StencilProblem& problem, const Objective& objective,
                                           const solvers::SolverInfo& solver, const AlphaSearchOptions& options = {},
                                           const solvers::SolverOptions& solver_options = {});

}  // namespace coons
