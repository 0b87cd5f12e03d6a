// The options that request a net (--method, --alpha, --mu, --solver, --mask, --weight and the
// stopping rules of solve, export and batch), checked against the boundary and resolved into a
// mask, a stencil and a backend here, once; the stencil path of files beyond the classical
// problem (two rings, free grids, --mask); the solve report of docs/formats.md.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "common.h"
#include "coons/io/boundary_io.h"
#include "coons/mask/mask9.h"
#include "coons/mask/solve_stencil_net.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"
#include "coons/study/net_report.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons::cli {

//! `--mask NAME` (docs/formats.md, Masks): the strings become this here, nowhere else.
enum class MaskKind { kAlpha, kC1Coons, kBiharmonic, kC1Family, kFile };

struct NetRequest {
  Method method = Method::kAlpha;
  double alpha = -0.25;
  std::optional<double> mu;
  std::string solver = "auto";
  bool allow_indefinite = false;
  double corner_tolerance = 1e-9;
  double tolerance = 1e-12;
  int max_iterations = 0;
  double time_limit = 0;  //!< --time-limit, seconds (SolverOptions::time_limit_seconds)
  double omega = 1.0;
  std::string mask = "alpha";    //!< --mask (solve only)
  std::optional<double> weight;  //!< --weight (c1-family)
  int threads = 1;               //!< --threads (SolverOptions::threads)
  CLI::Option* threads_option = nullptr;
  // which options were given (for contradictions)
  CLI::Option *method_option = nullptr, *alpha_option = nullptr, *mu_option = nullptr, *solver_option = nullptr,
              *tolerance_option = nullptr, *max_iterations_option = nullptr, *time_limit_option = nullptr,
              *omega_option = nullptr, *indefinite_option = nullptr, *mask_option = nullptr, *weight_option = nullptr;
};

struct ResolvedRequest {
  Method method = Method::kAlpha;
  Mask9 mask;
  const solvers::SolverInfo* solver = nullptr;  //!< concrete backend (alpha method only)
  bool picked_automatically = false;            //!< --solver auto chose it
  solvers::SolverOptions options;
  MaskKind mask_kind = MaskKind::kAlpha;
  std::string mask_name = "alpha";  //!< as given ("file:PATH" included)
  std::optional<double> weight;     //!< c1-family
  std::optional<Stencil> stencil;   //!< every mask but alpha (whose stencil is alpha_stencil(mask))
};

//! --method, --alpha, --mu, --solver, the stopping rules and --threads (solve, export, batch).
void add_net_options(CLI::App& cmd, NetRequest& r);
//! --mask and --weight (solve).
void add_mask_options(CLI::App& cmd, NetRequest& r);

//! Checks the request against the boundary; throws InputError naming the bad option (or both
//! options of a contradiction).
ResolvedRequest resolve(const NetRequest& r, const Boundary& boundary, const std::string& source);
//! --tolerance, --max-iterations or --time-limit given with a backend that solves exactly
//! (`solver`; nullptr for auto, which only picks such backends), or --time-limit with a hypre
//! backend (no clock in its iterations): InputError naming the option.
void refuse_stopping_rules(const NetRequest& r, const solvers::SolverInfo* solver);
//! The net of a classical request (a closed form, or the α mask solved by its backend).
NetOutcome make_net(const Boundary& boundary, const ResolvedRequest& r);

//! Input error (field `rings` or `free`) when the file is not the one-ring problem of a full
//! rectangle: for commands that solve only that problem (`what` names them in the message).
void require_one_ring(const BoundaryFile& input, const std::string& source, const std::string& what);
//! Non-zeros per matrix row of the request's stencil (9 for 3×3 masks, 25 for 5×5), for the
//! memory estimates.
int stencil_nonzeros(const ResolvedRequest& r);
//! True when the classical path applies: one data ring, no free grid, the alpha mask.
bool is_classical_request(const BoundaryFile& input, const ResolvedRequest& r);
//! The stencil path's check (require_valid_problem) for a classical --method alpha request: a mask
//! system that is singular on this grid (an α outside [−1/4, 1/4] at an eigenvalue of the mask
//! operator) is an InputError naming the points that decouple, whatever the backend; nothing for
//! the closed forms.
void check_classical_request(const BoundaryFile& input, const ResolvedRequest& r, const std::string& source);
//! The stencil of a resolved request.
Stencil request_stencil(const ResolvedRequest& r);

//! A stencil solve of a file beyond the classical problem, checked at the input edge first.
struct StencilRun {
  StencilProblem problem;
  Stencil stencil;
  StencilSolveResult result;
  bool picked_automatically = false;
};
//! Refuses closed-form methods beyond one ring and checks the problem (require_valid_problem:
//! InputError naming the field and the point); result is left empty.
StencilRun check_stencil_request(const BoundaryFile& input, const ResolvedRequest& r, const std::string& source);
//! check_stencil_request, then picks the solver (auto: the separable one when it applies, else a
//! sparse direct backend) and solves. The solve's trouble is in result.summary.
StencilRun solve_stencil_request(const BoundaryFile& input, const ResolvedRequest& r, const NetRequest& request,
                                 const GlobalOptions& global, const std::string& source);
nlohmann::json stencil_report(const BoundaryFile& input, const ResolvedRequest& r, const StencilRun& run,
                              const std::optional<double>& mu);
//! The solve report (docs/formats.md) without the timing block; metrics computed here.
nlohmann::json solve_report(const Boundary& boundary, const ResolvedRequest& r, const NetOutcome& outcome,
                            const std::optional<double>& mu);

}  // namespace coons::cli
