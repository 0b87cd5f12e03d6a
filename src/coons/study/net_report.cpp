#include "net_report.h"

#include <algorithm>
#include <cmath>

#include "coons/io/net_json.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/metrics/energies.h"
#include "coons/net/coons_net.h"

namespace coons {

using nlohmann::json;

const char* to_string(NetMethod m) {
  switch (m) {
    case NetMethod::kAlpha:
      return "alpha";
    case NetMethod::kCoons:
      return "coons";
    case NetMethod::kHermiteCoons:
      return "hermite-coons";
  }
  return "alpha";
}

NetOutcome make_net(const Boundary& boundary, NetMethod method, const Mask9& mask, const solvers::SolverInfo* solver,
                    const solvers::SolverOptions& options) {
  switch (method) {
    case NetMethod::kCoons:
      return {discrete_coons_net(boundary), std::nullopt};
    case NetMethod::kHermiteCoons:
      return {hermite_coons_net(boundary), std::nullopt};
    case NetMethod::kAlpha:
      break;
  }
  MaskSolveResult result = solve_mask_net(boundary, mask, *solver, options);
  return {std::move(result.net), std::move(result.summary)};
}

namespace {

// α, β (or β_ij) and μ of a 3×3 mask: μ given, or the μ of α at degree n (docs/math.md §4) when
// m = n and α ∈ [−1/4, 0).
void alpha_fields(json& report, const Boundary& boundary, const Mask9& mask, const std::optional<double>& mu) {
  report["alpha"] = mask.diag;
  report["beta"] = number_or_null(mask.edge_i == mask.edge_j ? mask.edge_i : NAN);
  if (mask.edge_i != mask.edge_j) report["beta_ij"] = {mask.edge_i, mask.edge_j};
  if (mu)
    report["mu"] = *mu;
  else if (boundary.m == boundary.n && mask.diag >= -0.25 && mask.diag < 0 && mask.edge_i == mask.edge_j)
    report["mu"] = mu_from_alpha(boundary.n, mask.diag);
  else
    report["mu"] = nullptr;
}

}  // namespace

json solver_block(const std::optional<solvers::SolveSummary>& summary, bool picked_automatically) {
  if (!summary)
    return {{"name", "closed-form"},
            {"status", "not_applicable"},
            {"message", "closed-form net: no linear system is solved"}};
  json block = summary_to_json(*summary);
  if (picked_automatically) block["picked_by"] = "auto";
  return block;
}

json net_report(const Boundary& boundary, NetMethod method, const Mask9& mask, const NetOutcome& outcome,
                const std::optional<double>& mu, bool solver_picked_automatically, bool with_net, int threads) {
  json report;
  report["boundary"] = boundary.name;
  report["degree"] = {boundary.m, boundary.n};
  report["method"] = to_string(method);
  // The alpha method, or a closed form: then the mask its mask_residual is measured against
  // (--alpha, default −1/4, which the Coons net satisfies exactly and the partially bicubic net
  // does not: its residual says how far it lies from the Coons net's mask).
  report["mask"] = "alpha";
  alpha_fields(report, boundary, mask, mu);
  report["rings"] = 1;
  report["free_points"] = std::max(boundary.m - 1, 0) * std::max(boundary.n - 1, 0);
  report["solver"] = solver_block(outcome.summary, solver_picked_automatically);
  const bool ok = !outcome.summary || outcome.summary->ok();
  if (!ok)
    report["net"] = nullptr;
  else if (with_net)
    report["net"] = net_to_json(outcome.net);
  report["metrics"] = ok ? metrics_to_json(net_metrics(outcome.net, mask, threads)) : json(nullptr);
  return report;
}

}  // namespace coons

namespace coons {

json stencil_net_report(const Boundary& boundary, const StencilProblem& problem, const Stencil& stencil,
                        const MaskLabel& label, const StencilSolveResult& result, const std::optional<double>& mu,
                        bool solver_picked_automatically) {
  json report;
  report["boundary"] = boundary.name;
  report["degree"] = {boundary.m, boundary.n};
  report["method"] = to_string(NetMethod::kAlpha);
  report["mask"] = label.name;
  if (label.weight) report["weight"] = *label.weight;
  if (label.mask9) {
    alpha_fields(report, boundary, *label.mask9, mu);
  } else {
    report["alpha"] = nullptr;
    report["beta"] = nullptr;
    report["mu"] = nullptr;
  }
  const FreeGrid free = free_points(problem);
  report["rings"] = problem.rings;
  report["free_points"] = free.count();
  report["solver"] = summary_to_json(result.summary);
  if (solver_picked_automatically) report["solver"]["picked_by"] = "auto";
  const bool ok = result.summary.ok();
  report["net"] = ok ? net_to_json(result.net) : json(nullptr);
  report["metrics"] = ok ? metrics_to_json(net_metrics(result.net, free, stencil)) : json(nullptr);
  return report;
}

}  // namespace coons
