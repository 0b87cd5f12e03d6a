// One net from a boundary, by the method asked for, and its report (docs/formats.md, `coons
// solve`): the mask, μ, the solver block, the net and every metric. Shared by solve, export and
// batch. stencil_net_report is the report of a mask problem beyond the classical one (two data
// rings, a free grid, a 5×5 mask: solve_stencil_net), with the same fields.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "coons/mask/mask9.h"
#include "coons/mask/solve_stencil_net.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

enum class NetMethod { kAlpha, kCoons, kHermiteCoons };
const char* to_string(NetMethod method);

struct NetOutcome {
  ControlNet net;
  std::optional<solvers::SolveSummary> summary;  //!< the alpha method only
};

//! kAlpha solves the mask system with `solver` (required then); the others are closed forms.
NetOutcome make_net(const Boundary& boundary, NetMethod method, const Mask9& mask, const solvers::SolverInfo* solver,
                    const solvers::SolverOptions& options = {});

//! The report's "solver" block: the summary of a solve ("picked_by": "auto" when auto chose the
//! backend), or the closed form's not_applicable block when no system was solved.
nlohmann::json solver_block(const std::optional<solvers::SolveSummary>& summary, bool picked_automatically);

//! The solve report without a timing block; `mu` as given on the command line, if it was. With
//! `with_net` false a successful net is left out of it, for the caller to write (write_net_json).
//! `threads` (0: every core) share out the exact energies (net_metrics).
nlohmann::json net_report(const Boundary& boundary, NetMethod method, const Mask9& mask, const NetOutcome& outcome,
                          const std::optional<double>& mu, bool solver_picked_automatically, bool with_net = true,
                          int threads = 1);

//! Which mask a stencil report names: `name` as the user gave it ("c1-family", "file:PATH"), the
//! weight of the C1 family, the 3×3 mask when it is the alpha family (α, β, μ are reported then).
struct MaskLabel {
  std::string name = "alpha";
  std::optional<double> weight;
  std::optional<Mask9> mask9;
};

//! The report of a stencil solve: method "alpha", "mask", "weight" (when set), "rings",
//! "free_points", α/β/μ (null unless mask9), the solver block, the net and every metric with
//! mask_residual the largest residual of `stencil`'s equations over the free points.
nlohmann::json stencil_net_report(const Boundary& boundary, const StencilProblem& problem, const Stencil& stencil,
                                  const MaskLabel& label, const StencilSolveResult& result,
                                  const std::optional<double>& mu, bool solver_picked_automatically);

}  // namespace coons
