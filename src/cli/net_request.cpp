#include "net_request.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/stencil_json.h"
#include "coons/study/memory_estimate.h"

namespace coons::cli {

using nlohmann::json;

void add_net_options(CLI::App& cmd, NetRequest& r) {
  const std::map<std::string, Method> methods = {
      {"alpha", Method::kAlpha}, {"coons", Method::kCoons}, {"hermite-coons", Method::kHermiteCoons}};
  r.method_option = cmd.add_option("--method", r.method,
                                   "alpha (solve the mask system), coons (closed form), "
                                   "hermite-coons (closed-form partially bicubic net, degree >= 3)")
                        ->transform(choice_of(methods))
                        ->default_str("alpha");
  r.alpha_option = cmd.add_option("--alpha", r.alpha, "weight of the diagonal neighbours; beta = 1/4 - alpha")
                       ->transform(fold_negative_zero())
                       ->capture_default_str();
  r.mu_option = cmd.add_option("--mu", r.mu,
                               "membrane weight of ∫‖p_uv‖² + μ∫‖∇p‖²: the anisotropic mask of "
                               "docs/math.md §3 (instead of --alpha)")
                    ->transform(fold_negative_zero());
  r.solver_option = cmd.add_option("--solver", r.solver, "a name from `coons solvers`, or auto")->capture_default_str();
  r.indefinite_option =
      cmd.add_flag("--allow-indefinite", r.allow_indefinite,
                   "let Cholesky-type solvers run outside alpha in [-1/4, 1/4] (they will report it)");
  cmd.add_option("--corner-tolerance", r.corner_tolerance,
                 "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  r.tolerance_option = cmd.add_option("--tolerance", r.tolerance, "iterative solvers: relative residual to reach")
                           ->capture_default_str();
  r.max_iterations_option =
      cmd.add_option("--max-iterations", r.max_iterations, "iterative solvers: limit (0: automatic)")
          ->capture_default_str();
  r.time_limit_option =
      cmd.add_option("--time-limit", r.time_limit,
                     "iterative solvers: stop a solve after this many seconds, not_converged "
                     "with the iterate reached (0: none; not the hypre backends, which have no clock)")
          ->capture_default_str();
  r.omega_option =
      cmd.add_option("--omega", r.omega, "gauss-seidel: over-relaxation factor in (0, 2)")->capture_default_str();
  r.threads_option = add_threads_option(cmd, r.threads);
}

void add_mask_options(CLI::App& cmd, NetRequest& r) {
  r.mask_option = cmd.add_option("--mask", r.mask,
                                 "alpha (the 3x3 family, --alpha/--mu), c1-coons, biharmonic, c1-family "
                                 "(--weight), or file:PATH (a stencil file, docs/formats.md)")
                      ->capture_default_str();
  r.weight_option = cmd.add_option("--weight", r.weight, "c1-family: w in [0, 1] (1: c1-coons, 0: biharmonic)")
                        ->transform(fold_negative_zero());
}

namespace {

// --mask and --weight: the stencil of every mask but alpha, and their contradictions.
void resolve_mask(const NetRequest& r, ResolvedRequest& out) {
  out.mask_name = r.mask;
  const std::string file_prefix = "file:";
  if (r.mask == "alpha") {
    out.mask_kind = MaskKind::kAlpha;
  } else if (r.mask == "c1-coons") {
    out.mask_kind = MaskKind::kC1Coons;
  } else if (r.mask == "biharmonic") {
    out.mask_kind = MaskKind::kBiharmonic;
  } else if (r.mask == "c1-family") {
    out.mask_kind = MaskKind::kC1Family;
  } else if (r.mask.rfind(file_prefix, 0) == 0) {
    out.mask_kind = MaskKind::kFile;
    if (r.mask.size() == file_prefix.size())
      throw InputError("command line", "--mask", "file: needs the path of a stencil file (--mask file:PATH)");
  } else {
    throw InputError("command line", "--mask",
                     "unknown mask '" + r.mask + "' (alpha, c1-coons, biharmonic, c1-family, file:PATH)");
  }
  if (out.mask_kind != MaskKind::kAlpha) {
    for (const auto& [option, name] : {std::pair{r.alpha_option, "--alpha"}, std::pair{r.mu_option, "--mu"}})
      if (given(option))
        throw InputError(
            "command line", name,
            fmt::format("{} chooses the 3x3 mask of --mask alpha; it does not apply to --mask {}", name, r.mask));
    // (it was accepted and did nothing: the check it relaxes is of alpha outside [-1/4, 1/4])
    if (given(r.indefinite_option))
      throw InputError("command line", "--allow-indefinite",
                       "--allow-indefinite lets Cholesky-type solvers run at an alpha outside [-0.25, 0.25]; it does "
                       "not apply to --mask " +
                           r.mask);
  }
  if (given(r.weight_option) && out.mask_kind != MaskKind::kC1Family)
    throw InputError("command line", "--weight",
                     "--weight is the w of --mask c1-family; it does not apply to --mask " + r.mask);
  switch (out.mask_kind) {
    case MaskKind::kAlpha:
      return;
    case MaskKind::kC1Coons:
      out.stencil = c1_coons_stencil();
      return;
    case MaskKind::kBiharmonic:
      out.stencil = biharmonic_stencil();
      return;
    case MaskKind::kC1Family:
      if (!r.weight) throw InputError("command line", "--weight", "--mask c1-family needs --weight w in [0, 1]");
      if (!(*r.weight >= 0 && *r.weight <= 1))
        throw InputError("command line", "--weight", fmt::format("must be a number in [0, 1], got {}", *r.weight));
      out.weight = r.weight;
      out.stencil = c1_family_stencil(*r.weight);
      return;
    case MaskKind::kFile: {
      const std::string path = r.mask.substr(file_prefix.size());
      out.stencil = stencil_from_json(read_json_file(path), path);
      return;
    }
  }
}

}  // namespace

void refuse_stopping_rules(const NetRequest& r, const solvers::SolverInfo* solver) {
  for (auto [option, name] : {std::pair{r.tolerance_option, "--tolerance"},
                              {r.max_iterations_option, "--max-iterations"},
                              {r.time_limit_option, "--time-limit"}}) {
    if (!given(option)) continue;
    if (!solver)  // auto only ever picks a direct or structured backend
      throw InputError(
          "command line", name,
          fmt::format("{} is a stopping rule of the iterative solvers; --solver auto picks one that solves "
                      "exactly (name an iterative one with --solver)",
                      name));
    if (solver->family != solvers::SolverFamily::kIterative)
      throw InputError("command line", name,
                       fmt::format("{} is a stopping rule of the iterative solvers; {} is a {} solver and solves "
                                   "exactly",
                                   name, solver->name, solvers::to_string(solver->family)));
    if (option == r.time_limit_option && solver->name.rfind("hypre-", 0) == 0)
      throw InputError("command line", name,
                       fmt::format("{} has no clock in its iterations: --time-limit would not stop it (use "
                                   "--max-iterations)",
                                   solver->name));
  }
}

ResolvedRequest resolve(const NetRequest& r, const Boundary& boundary, const std::string& source) {
  ResolvedRequest out;
  out.method = r.method;
  // Contradictions: options that would be ignored are errors naming both. A closed form takes
  // --alpha and --mu (they choose the mask its mask_residual is measured against) and the
  // defaults --solver auto and --mask alpha, which ask for nothing it does not do.
  if (out.method != Method::kAlpha) {
    const CLI::Option* solver_option = r.solver == "auto" ? nullptr : r.solver_option;
    const CLI::Option* mask_option = r.mask == "alpha" ? nullptr : r.mask_option;
    const std::pair<const CLI::Option*, const char*> alpha_only[] = {{solver_option, "--solver"},
                                                                     {r.tolerance_option, "--tolerance"},
                                                                     {r.max_iterations_option, "--max-iterations"},
                                                                     {r.time_limit_option, "--time-limit"},
                                                                     {r.omega_option, "--omega"},
                                                                     {r.indefinite_option, "--allow-indefinite"},
                                                                     {mask_option, "--mask"},
                                                                     {r.weight_option, "--weight"}};
    for (const auto& [option, name] : alpha_only)
      if (given(option))
        throw InputError("command line", "--method",
                         fmt::format("--method {} is a closed form: {} does not apply (it needs --method alpha)",
                                     to_string(out.method), name));
  }
  if (given(r.alpha_option) && given(r.mu_option))
    throw InputError("command line", "--alpha", "--alpha and --mu both choose the mask; give one of them");
  if (given(r.omega_option) && r.solver != "gauss-seidel")
    throw InputError("command line", "--omega",
                     "--omega is the over-relaxation of --solver gauss-seidel, not of " + r.solver);
  if (r.solver == "auto")
    refuse_stopping_rules(r, nullptr);
  else if (const solvers::SolverInfo* named = solvers::find_solver(r.solver))  // an unknown name is refused below
    refuse_stopping_rules(r, named);

  resolve_mask(r, out);
  require_alpha_value(r.alpha);
  if (r.mu && !(std::isfinite(*r.mu) && *r.mu >= 0))
    throw InputError("command line", "--mu", "must be a finite number >= 0");
  out.mask = r.mu ? anisotropic_mask(boundary.m, boundary.n, *r.mu) : alpha_mask(r.alpha);

  out.options = threads_options(r.threads, r.threads_option, r.solver);
  out.options.tolerance = r.tolerance;
  out.options.max_iterations = r.max_iterations;
  out.options.time_limit_seconds = r.time_limit;
  out.options.sor_omega = r.omega;
  require_valid_solver_options(out.options);

  if (out.method == Method::kHermiteCoons && (boundary.m < 3 || boundary.n < 3))
    throw InputError(source, "degree",
                     fmt::format("hermite-coons needs degree >= 3 in both directions, the boundary has ({}, {})",
                                 boundary.m, boundary.n));
  if (out.method != Method::kAlpha) return out;

  const auto stencil = mask_stencil(out.mask, std::max(boundary.m - 1, 0), std::max(boundary.n - 1, 0));
  out.solver = solver_from_name(r.solver);
  if (!out.solver) {
    out.solver = solvers::find_solver(stencil.size() > 0 ? solvers::choose_auto_solver(stencil) : "eigen-ldlt");
    out.picked_automatically = true;
    return out;
  }
  const double alpha_equiv = out.mask.diag;
  const bool in_definite_range = alpha_equiv >= -0.25 && alpha_equiv <= 0.25;
  if (out.solver->definite_only && !in_definite_range && !r.allow_indefinite)
    throw InputError("command line", "--alpha",
                     fmt::format("{} is outside [-0.25, 0.25], where the mask system of {} is positive definite; "
                                 "{} needs that (use eigen-lu, or --allow-indefinite to try anyway)",
                                 alpha_equiv, source, r.solver));
  return out;
}

namespace {

// The options of a solve by `info`: with the condition estimate where the backend factors the
// assembled matrix or iterates, whose small residual can hide a large error
// (SolverOptions::estimate_condition). Not for the structured backends: they solve the grid
// operator itself, more accurately than κ·ε says (docs/solvers.md, Accuracy).
solvers::SolverOptions options_for(const ResolvedRequest& r, const solvers::SolverInfo* info) {
  solvers::SolverOptions options = r.options;
  options.estimate_condition = info && (info->needs_matrix || info->family == solvers::SolverFamily::kIterative);
  return options;
}

}  // namespace

NetOutcome make_net(const Boundary& boundary, const ResolvedRequest& r) {
  return coons::make_net(boundary, r.method, r.mask, r.solver, options_for(r, r.solver));
}

json solve_report(const Boundary& boundary, const ResolvedRequest& r, const NetOutcome& outcome,
                  const std::optional<double>& mu) {
  return net_report(boundary, r.method, r.mask, outcome, mu, r.picked_automatically);
}

bool is_classical_request(const BoundaryFile& input, const ResolvedRequest& r) {
  return is_classical(input) && r.mask_kind == MaskKind::kAlpha;
}

void check_classical_request(const BoundaryFile& input, const ResolvedRequest& r, const std::string& source) {
  if (r.method != Method::kAlpha) return;
  // The closed-form eigenvalues settle a clearly regular system in O(mn); only a near-singular one
  // pays for require_valid_problem's search (a sparse LU of the whole interior), which names the
  // points that decouple. The ratio's threshold (1e-6) is far above that check's (1e-10 of
  // ‖A‖₁ ≥ max|λ|). The α search refuses to evaluate outside [−1/4, 1/4] below the same ratio.
  if (mask9_eigenvalue_ratio(r.mask, input.boundary.m, input.boundary.n) > kNearSingularEigenvalueRatio) return;
  // The file of a classical request has no free grid: what makes its system singular is the α of
  // --alpha (--mu's masks are definite), which the error names (it named "free[1][1]" of a file
  // that has no "free").
  const std::vector<ProblemIssue> issues = check_stencil_problem(stencil_problem(input), alpha_stencil(r.mask));
  if (!issues.empty())
    throw InputError("command line", "--alpha",
                     fmt::format("alpha = {} on the {} by {} net of {}: {}", r.mask.diag, input.boundary.m + 1,
                                 input.boundary.n + 1, source, issues.front().reason));
}

Stencil request_stencil(const ResolvedRequest& r) { return r.stencil ? *r.stencil : alpha_stencil(r.mask); }

void require_one_ring(const BoundaryFile& input, const std::string& source, const std::string& what) {
  if (is_classical(input)) return;
  const bool rings = input.rings > 1;
  // the field the file gives: a sides-form file has its second ring as "ribbons", and no "rings"
  const char* field = !rings ? "free" : input.ribbons ? "ribbons" : "rings";
  throw InputError(source, field,
                   fmt::format("{} works on the one-ring problem of a full rectangle, and this file has {}; solve "
                               "it with `coons solve --alpha A` or `coons batch --alphas ...`",
                               what, rings ? fmt::format("{} data rings", input.rings) : std::string("a free grid")));
}

int stencil_nonzeros(const ResolvedRequest& r) {
  return r.stencil && r.stencil->radius == 2 ? kStencil5Nonzeros : kMask3Nonzeros;
}

StencilRun check_stencil_request(const BoundaryFile& input, const ResolvedRequest& r, const std::string& source) {
  if (r.method != Method::kAlpha)
    throw InputError(
        "command line", "--method",
        fmt::format("--method {} is a closed form over one data ring, but {} has {}; use --method alpha "
                    "(a --mask solve)",
                    to_string(r.method), source,
                    input.rings > 1 ? fmt::format("{} data rings", input.rings) : std::string("a free grid")));
  StencilRun run;
  run.problem = stencil_problem(input);
  run.stencil = request_stencil(r);
  require_valid_problem(run.problem, run.stencil, source);
  return run;
}

StencilRun solve_stencil_request(const BoundaryFile& input, const ResolvedRequest& r, const NetRequest& request,
                                 const GlobalOptions& global, const std::string& source) {
  check_net_memory(global, input.boundary, request.solver == "auto" ? nullptr : r.solver, source, stencil_nonzeros(r));
  StencilRun run = check_stencil_request(input, r, source);
  std::unique_ptr<solvers::LinearSolver> solver;
  if (request.solver == "auto") {
    run.picked_automatically = true;
    solver = make_structured_stencil_solver(run.problem, run.stencil, r.options);
    if (!solver) solver = make_factored_multigrid_solver(run.problem, run.stencil, r.options);
    if (!solver) {
      // Positive definite systems (the symbol is >= 0: every named mask, alpha in [-1/4, 1/4]):
      // sparse Cholesky; others a sparse LU.
      const solvers::SolverInfo& info = solvers::default_matrix_solver(symbol_nonnegative(run.stencil));
      solver = solvers::make_solver(info.name, options_for(r, &info));
    }
  } else {
    solver = solvers::make_solver(r.solver->name, options_for(r, r.solver));
  }
  run.result = solve_stencil_net(run.problem, run.stencil, *solver);
  return run;
}

json stencil_report(const BoundaryFile& input, const ResolvedRequest& r, const StencilRun& run,
                    const std::optional<double>& mu) {
  MaskLabel label;
  label.name = r.mask_name;
  label.weight = r.weight;
  if (r.mask_kind == MaskKind::kAlpha) label.mask9 = r.mask;
  return stencil_net_report(input.boundary, run.problem, run.stencil, label, run.result, mu, run.picked_automatically);
}

}  // namespace coons::cli
