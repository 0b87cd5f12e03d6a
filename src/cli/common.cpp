#include "common.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/metrics/energies.h"
#include "coons/net/coons_net.h"
#include "solvers/registry.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;



const char* to_string(Method m) {
  switch (m) {
    case Method::kAlpha: return "alpha";
    case Method::kCoons: return "coons";
    case Method::kHermiteCoons: return "hermite-coons";
  }
  return "alpha";
}

// What `solve`, `export` and `batch` share: how to make a net from a boundary.

void add_net_options(CLI::App& cmd, NetRequest& r) {
  cmd.add_option("--method", r.method, "alpha (solve the mask system), coons (closed form), "
                 "hermite-coons (closed-form partially bicubic net, degree >= 3)")
      ->capture_default_str();
  cmd.add_option("--alpha", r.alpha, "weight of the diagonal neighbours; beta = 1/4 - alpha")
      ->capture_default_str();
  cmd.add_option("--mu", r.mu, "membrane weight of ∫‖p_uv‖² + μ∫‖∇p‖²: the anisotropic mask of "
                 "docs/math.md §3 (overrides --alpha)");
  cmd.add_option("--solver", r.solver, "a name from `coons solvers`, or auto")->capture_default_str();
  cmd.add_flag("--allow-indefinite", r.allow_indefinite,
                "let Cholesky-type solvers run outside alpha in [-1/4, 1/4] (they will report it)");
  cmd.add_option("--corner-tolerance", r.corner_tolerance,
                 "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  cmd.add_option("--tolerance", r.tolerance, "iterative solvers: relative residual to reach")
      ->capture_default_str();
  cmd.add_option("--max-iterations", r.max_iterations, "iterative solvers: limit (0: automatic)")
      ->capture_default_str();
  cmd.add_option("--omega", r.omega, "gauss-seidel: over-relaxation factor in (0, 2)")->capture_default_str();
}

// A validated request: strings turned into enums, backend names checked.

ResolvedRequest resolve(const NetRequest& r, const Boundary& boundary, const std::string& source) {
  ResolvedRequest out;
  if (r.method == "alpha") out.method = Method::kAlpha;
  else if (r.method == "coons") out.method = Method::kCoons;
  else if (r.method == "hermite-coons") out.method = Method::kHermiteCoons;
  else throw InputError("command line", "--method", "unknown method '" + r.method + "' (alpha, coons, hermite-coons)");

  if (!std::isfinite(r.alpha)) throw InputError("command line", "--alpha", "must be a finite number");
  if (r.mu && !(std::isfinite(*r.mu) && *r.mu >= 0))
    throw InputError("command line", "--mu", "must be a finite number >= 0");
  out.mask = r.mu ? anisotropic_mask(boundary.m, boundary.n, *r.mu) : alpha_mask(r.alpha);

  out.options.tolerance = r.tolerance;
  out.options.max_iterations = r.max_iterations;
  out.options.sor_omega = r.omega;
  std::string why;
  if (!out.options.is_valid(&why)) throw InputError("command line", "solver options", why);

  if (out.method == Method::kHermiteCoons && (boundary.m < 3 || boundary.n < 3))
    throw InputError(source, "degree",
                     fmt::format("hermite-coons needs degree >= 3 in both directions, the boundary has ({}, {})",
                                 boundary.m, boundary.n));
  if (out.method != Method::kAlpha) return out;

  const auto stencil = mask_stencil(out.mask, std::max(boundary.m - 1, 0), std::max(boundary.n - 1, 0));
  out.solver = r.solver;
  if (r.solver == "auto") {
    out.solver = stencil.size() > 0 ? solvers::choose_auto_solver(stencil) : "eigen-ldlt";
    out.picked_automatically = true;
    return out;
  }
  const solvers::SolverInfo* info = solvers::find_solver(r.solver);
  if (!info) {
    std::string names;
    for (const auto& s : solvers::available_solvers()) names += (names.empty() ? "" : ", ") + s.name;
    throw InputError("command line", "--solver", "unknown solver '" + r.solver + "' (built in: auto, " + names + ")");
  }
  const double alpha_equiv = out.mask.diag;
  const bool in_definite_range = alpha_equiv >= -0.25 && alpha_equiv <= 0.25;
  if (info->definite_only && !in_definite_range && !r.allow_indefinite)
    throw InputError("command line", "--alpha",
                     fmt::format("{} is outside [-0.25, 0.25], where the system is positive definite; "
                                 "{} needs that (use eigen-lu, or --allow-indefinite to try anyway)",
                                 alpha_equiv, r.solver));
  return out;
}


NetOutcome make_net(const Boundary& boundary, const ResolvedRequest& r) {
  switch (r.method) {
    case Method::kCoons: return {discrete_coons_net(boundary), std::nullopt};
    case Method::kHermiteCoons: return {hermite_coons_net(boundary), std::nullopt};
    case Method::kAlpha: break;
  }
  MaskSolveResult result = solve_mask_net(boundary, r.mask, r.solver, r.options);
  return {std::move(result.net), std::move(result.summary)};
}

json solve_report(const Boundary& boundary, const ResolvedRequest& r, const NetOutcome& outcome,
                  const std::optional<double>& mu) {
  json report;
  report["boundary"] = boundary.name;
  report["degree"] = {boundary.m, boundary.n};
  report["method"] = to_string(r.method);
  report["alpha"] = r.mask.diag;
  report["beta"] = number_or_null(r.mask.edge_i == r.mask.edge_j ? r.mask.edge_i : NAN);
  if (r.mask.edge_i != r.mask.edge_j) report["beta_ij"] = {r.mask.edge_i, r.mask.edge_j};
  // μ next to α: given, or the μ of α at degree n (docs/math.md §4) when m = n and α ∈ [−1/4, 0).
  if (mu) report["mu"] = *mu;
  else if (boundary.m == boundary.n && r.mask.diag >= -0.25 && r.mask.diag < 0 && r.mask.edge_i == r.mask.edge_j)
    report["mu"] = mu_from_alpha(boundary.n, r.mask.diag);
  else report["mu"] = nullptr;
  if (outcome.summary) {
    report["solver"] = summary_to_json(*outcome.summary);
    if (r.picked_automatically) report["solver"]["picked_by"] = "auto";
  }
  else report["solver"] = {{"name", "closed-form"}, {"status", "not_applicable"},
                           {"message", "closed-form net: no linear system is solved"}};
  const bool ok = !outcome.summary || outcome.summary->ok();
  report["net"] = ok ? net_to_json(outcome.net) : json(nullptr);
  report["metrics"] = ok ? metrics_to_json(net_metrics(outcome.net, r.mask)) : json(nullptr);
  return report;
}

BoundaryFile read_input(const std::string& path, const NetRequest& r) {
  BoundaryReadOptions options;
  if (!(r.corner_tolerance >= 0 && std::isfinite(r.corner_tolerance)))
    throw InputError("command line", "--corner-tolerance", "must be a finite number >= 0");
  options.corner_tolerance = r.corner_tolerance;
  return read_boundary_file(path, options);
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    if (fs::is_directory(in)) {
      std::vector<std::string> found;
      for (const auto& entry : fs::directory_iterator(in))
        if (entry.path().extension() == ".json") found.push_back(entry.path().string());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(in);
    }
  }
  return files;
}


}  // namespace coons::cli
