// Solve a stencil problem (any 3×3 or 5×5 mask, any free set, any number of data rings) with a
// solver object of the registry or a structured one: assemble (stencil_system.h), analyze,
// factorize, solve, and write the solution into the free points of the net.
//
//   solve_stencil_net      one stencil;
//   solve_stencil_sweep    a family of stencils of one radius on one problem (the C1 family over w,
//                          the α family): one assembly with the box pattern and one symbolic
//                          analysis; per member only the values are refilled, then factorize and
//                          solve (what LinearSolver::factorize reuses for a same-size operator);
//   make_separable_solver  the exact structured solver when the free set is a full rectangle and
//                          the stencil separable (c1-coons: Δ⁴_i Δ⁴_j, two batches of
//                          pentadiagonal solves; the α = −1/4 mask: tridiagonal), else nullptr;
//   make_structured_stencil_solver  for a symbol ≥ 0 (stencil.h: symbol_nonnegative): that, or
//                          fast5 where it applies (the C1 family), else nullptr.
// The backends get op.matrix when assembled, op.stencil (a GridStencil) when the stencil is
// 3×3 on a full rectangle, so the transform backends ("dst", "fast") solve the α family with any
// number of rings, and op.grid (the stencil on the free points' bounding rectangle with its free
// mask) always, for fast5, pcg-fast and the multigrid backends. Numerical trouble is a status in the summary, never an
// exception. Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/mask/stencil_system.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons {

struct StencilSolveOptions {
  //! with_matrix = false only for backends that need no matrix (structured ones, mask iterations).
  StencilAssemblyOptions assembly;
  //! Check the problem's structure first (shape, rings, points): cheap. The singularity check of
  //! check_stencil_problem is left to the caller (the input edge): a singular system shows as a
  //! solver status here.
  bool check_structure = true;
};

struct StencilSolveResult {
  ControlNet net;                 //!< the data with the solved free points (the input net on failure)
  solvers::SolveSummary summary;  //!< status, iterations, residual, seconds
  int unknowns = 0;               //!< the number of free points
};

StencilSolveResult solve_stencil_net(const StencilProblem& problem, const Stencil& stencil,
                                     solvers::LinearSolver& solver, const StencilSolveOptions& options = {});

using StencilSweepSink = std::function<void(std::size_t member, const StencilSolveResult& result)>;

//! members: stencils of one radius; sink(k, result_k) in order.
void solve_stencil_sweep(const StencilProblem& problem, const std::vector<Stencil>& members,
                         solvers::LinearSolver& solver, const StencilSweepSink& sink,
                         const StencilSolveOptions& options = {});

//! The "separable-banded" solver for this problem and stencil, or nullptr when the free set is
//! not a full rectangle or the stencil not separable.
std::unique_ptr<solvers::LinearSolver> make_separable_solver(const StencilProblem& problem, const Stencil& stencil,
                                                             const solvers::SolverOptions& options = {});

//! The exact structured solver of a 5×5 problem, for `--solver auto`: nullptr when the stencil's
//! symbol is negative somewhere (neither eliminates with pivoting); else "separable-banded" when
//! it applies, else "fast5" when it accepts the system (a full rectangle and a stencil a·C + b·T
//! of the C1 family with a, b ≥ 0: biharmonic, c1-family), else nullptr (the caller picks a
//! sparse direct solver).
std::unique_ptr<solvers::LinearSolver> make_structured_stencil_solver(const StencilProblem& problem,
                                                                      const Stencil& stencil,
                                                                      const solvers::SolverOptions& options = {});

//! For `--solver auto` where no exact structured solver applies: "mg-cg" when the stencil is a
//! multiple of integer factors p ⊗ q of radius 2 (c1-coons: solvers::integer_separable_form) and
//! the free points' bounding rectangle is at least kFactoredMultigridSide points each way; else
//! nullptr (the caller picks a sparse direct solver). There the condition number grows like N⁸ and
//! a sparse factorisation of the rounded weights loses the net's smooth part (on a cubic net with a
//! hole, max error 2.0e−8 at degree 64 and 2.5e−6 at 128; `cholmod` at N = 511 stops with
//! not_positive_definite), while `mg-cg` keeps the integer factors (2.0e−9 and 1.0e−8). Below that size
//! the two are about equally accurate (1e−10 at degree 32) and the direct solve stays.
constexpr int kFactoredMultigridSide = 64;
std::unique_ptr<solvers::LinearSolver> make_factored_multigrid_solver(const StencilProblem& problem,
                                                                      const Stencil& stencil,
                                                                      const solvers::SolverOptions& options = {});

}  // namespace coons
