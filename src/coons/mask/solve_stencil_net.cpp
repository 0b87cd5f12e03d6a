#include "solve_stencil_net.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "coons/mask/centred_solve.h"
#include "coons/mask/stencil.h"
#include "solvers/registry.h"
#include "solvers/separable_banded_solver.h"
#include "solvers/stencil_operator.h"

namespace coons {

namespace {

// The first structural issue as a summary message, or empty.
std::string structural_issue(const StencilProblem& problem, const Stencil& stencil) {
  ProblemCheckOptions check;
  check.check_singular = false;
  const auto issues = check_stencil_problem(problem, stencil, check);
  if (issues.empty()) return {};
  return "the problem does not fit the mask: " + issues.front().field + ": " + issues.front().reason;
}

solvers::LinearOperator operator_of(const StencilSystem& system) {
  solvers::LinearOperator op;
  if (system.A.rows() > 0) op.matrix = &system.A;
  op.stencil = system.grid;
  if (system.grid_operator.rows > 0) op.grid = &system.grid_operator;
  return op;
}

StencilSolveResult not_applicable(const StencilProblem& problem, const solvers::LinearSolver& solver,
                                  std::string message) {
  StencilSolveResult result;
  result.net = problem.net;
  result.summary.solver = solver.name();
  result.summary.status = solvers::SolveStatus::kNotApplicable;
  result.summary.message = std::move(message);
  result.summary.relative_residual = 1;  // of X = 0, what a failed solve returns (docs/formats.md)
  return result;
}

// A stencil that reproduces constants (weights summing to 0 to rounding: every named mask) is
// solved for the data moved to their centre, the solution moved back: the net does not depend on
// where the data lie, its digits do (a 9 × 7 two-ring net at 1e12 came back 0.028 off from the
// sparse direct solvers and 4.3 off from cg, both "success", in a shape of size 18).
bool reproduces_constants(const Stencil& stencil) {
  return std::abs(stencil.weights.sum()) <= 1e-14 * stencil.weights.cwiseAbs().sum();
}

Eigen::RowVector3d solve_centre(const StencilProblem& problem, const Stencil& stencil) {
  return reproduces_constants(stencil) ? data_centre(problem, {stencil}) : Eigen::RowVector3d::Zero();
}

StencilProblem moved(StencilProblem problem, const Eigen::RowVector3d& centre) {
  problem.net.points.rowwise() -= centre;
  return problem;
}

StencilSolveResult solve_assembled(const StencilProblem& problem, const Stencil& stencil, const StencilSystem& system,
                                   solvers::LinearSolver& solver, bool analyze, const Eigen::RowVector3d& centre) {
  StencilSolveResult result;
  result.unknowns = system.numbering.size();
  if (result.unknowns == 0) {  // nothing free: the data are the answer
    result.net = problem.net;
    result.summary.solver = solver.name();
    return result;
  }
  const solvers::LinearOperator op = operator_of(system);
  Eigen::MatrixX3d X;
  if (analyze) {
    result.summary = solver.compute_and_solve(op, system.B, X);
  } else {
    solver.factorize(op);  // a failed one leaves solve() X = 0 and the status that says why
    result.summary = solver.solve(system.B, X);
  }
  finish_centred_solve(
      solver, op, [&] { return stencil_rhs(problem.net, system.numbering, stencil); }, weight_sum(stencil.weights),
      centre, X, result.summary);
  result.net = result.summary.ok() ? fill_free_points(problem.net, system.numbering, X) : problem.net;
  return result;
}

}  // namespace

StencilSolveResult solve_stencil_net(const StencilProblem& problem, const Stencil& stencil,
                                     solvers::LinearSolver& solver, const StencilSolveOptions& options) {
  if (options.check_structure) {
    if (std::string why = structural_issue(problem, stencil); !why.empty())
      return not_applicable(problem, solver, std::move(why));
  }
  const Eigen::RowVector3d centre = solve_centre(problem, stencil);
  const StencilSystem system = assemble_stencil_system(moved(problem, centre), stencil, options.assembly);
  return solve_assembled(problem, stencil, system, solver, true, centre);
}

void solve_stencil_sweep(const StencilProblem& problem, const std::vector<Stencil>& members,
                         solvers::LinearSolver& solver, const StencilSweepSink& sink,
                         const StencilSolveOptions& options) {
  if (members.empty()) return;
  if (options.check_structure) {
    if (std::string why = structural_issue(problem, members.front()); !why.empty()) {
      for (std::size_t k = 0; k < members.size(); ++k) sink(k, not_applicable(problem, solver, why));
      return;
    }
  }
  StencilAssemblyOptions assembly = options.assembly;
  assembly.box_pattern = true;  // one pattern for every member
  // (moved to the data's centre when every member reproduces constants)
  const bool invariant = std::all_of(members.begin(), members.end(), reproduces_constants);
  const Eigen::RowVector3d centre = invariant ? data_centre(problem, members) : Eigen::RowVector3d::Zero();
  const StencilProblem centred = moved(problem, centre);
  StencilSystem system = assemble_stencil_system(centred, members.front(), assembly);
  for (std::size_t k = 0; k < members.size(); ++k) {
    if (k > 0 && !refill_stencil_system(centred, members[k], system)) {
      sink(k, not_applicable(problem, solver, "sweep members must share the radius of the first"));
      continue;
    }
    // Only the first member analyzes; factorize re-analyzes by itself if that analysis failed.
    sink(k, solve_assembled(problem, members[k], system, solver, k == 0, centre));
  }
}

std::unique_ptr<solvers::LinearSolver> make_separable_solver(const StencilProblem& problem, const Stencil& stencil,
                                                             const solvers::SolverOptions& options) {
  StencilAssemblyOptions assembly;
  assembly.with_matrix = false;
  const StencilSystem system = assemble_stencil_system(problem, stencil, assembly);
  if (!system.separable) return nullptr;
  return solvers::make_separable_banded_solver(*system.separable, options);
}

std::unique_ptr<solvers::LinearSolver> make_structured_stencil_solver(const StencilProblem& problem,
                                                                      const Stencil& stencil,
                                                                      const solvers::SolverOptions& options) {
  // The structured solvers eliminate without pivoting (separable-banded) or need a·C + b·T with
  // a, b ≥ 0 (fast5): a symbol negative somewhere goes to a pivoting sparse LU.
  if (!symbol_nonnegative(stencil)) return nullptr;
  if (auto separable = make_separable_solver(problem, stencil, options)) return separable;
  if (!solvers::find_solver("fast5")) return nullptr;  // built without FFTW
  StencilAssemblyOptions assembly;
  assembly.with_matrix = false;
  const StencilSystem system = assemble_stencil_system(problem, stencil, assembly);
  if (system.numbering.size() == 0 || system.grid_operator.rows == 0) return nullptr;
  auto fast5 = solvers::make_solver("fast5", options);
  if (fast5->analyze(operator_of(system)) != solvers::SolveStatus::kSuccess) return nullptr;
  return fast5;  // analyzed on a system that goes out of scope here: the solve analyzes again
}

std::unique_ptr<solvers::LinearSolver> make_factored_multigrid_solver(const StencilProblem& problem,
                                                                      const Stencil& stencil,
                                                                      const solvers::SolverOptions& options) {
  if (stencil.radius != 2 || !symbol_nonnegative(stencil) || !solvers::find_solver("mg-cg")) return nullptr;
  StencilAssemblyOptions assembly;
  assembly.with_matrix = false;
  const StencilSystem system = assemble_stencil_system(problem, stencil, assembly);
  const solvers::StencilOperator& grid = system.grid_operator;
  if (system.numbering.size() == 0 || std::min(grid.rows, grid.cols) < kFactoredMultigridSide) return nullptr;
  if (!solvers::integer_separable_form(grid)) return nullptr;
  return solvers::make_solver("mg-cg", options);
}

}  // namespace coons
