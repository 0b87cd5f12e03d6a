#include "coons/study/tri_report.h"

#include <cmath>

#include "coons/io/net_json.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/study/search_report.h"

namespace coons {

using nlohmann::json;

json tri_metrics_to_json(const tri::TriNetMetrics& m) {
  return {{"dirichlet_energy", number_or_null(m.dirichlet_energy)},
          {"thin_plate_energy", number_or_null(m.thin_plate_energy)},
          {"twist_energy", number_or_null(m.twist_energy)},
          {"e3_energy", number_or_null(m.e3_energy)},
          {"discrete_dirichlet_energy", number_or_null(m.discrete_dirichlet_energy)},
          {"discrete_thin_plate_energy", number_or_null(m.discrete_thin_plate_energy)},
          {"discrete_twist_energy", number_or_null(m.discrete_twist_energy)},
          {"mask_residual", number_or_null(m.mask_residual)}};
}

json tri_solve_report(const tri::TriBoundary& boundary, const tri::TriMask& mask, const tri::TriSolveResult& result,
                      bool solver_picked_automatically) {
  json report;
  report["boundary"] = boundary.name;
  report["type"] = "triangle";
  report["degree"] = boundary.n;
  report["method"] = "alpha";
  report["alpha"] = mask.c;
  report["a"] = mask.a();
  report["solver"] = summary_to_json(result.summary);
  if (solver_picked_automatically) report["solver"]["picked_by"] = "auto";
  const bool ok = result.summary.ok();
  report["net"] = ok ? tri_net_to_json(result.net) : json(nullptr);
  report["metrics"] = ok ? tri_metrics_to_json(tri::tri_net_metrics(result.net, mask)) : json(nullptr);
  return report;
}

json tri_search_report(const tri::TriBoundary& boundary, const std::string& objective,
                       const AlphaSearchOptions& options, const AlphaSearchSummary& s) {
  json out;
  out["boundary"] = boundary.name;
  out["type"] = "triangle";
  out["degree"] = boundary.n;
  out["objective"] = objective;
  out["parameter"] = "c";
  out["alpha"] = s.parameter ? json(*s.parameter) : json(nullptr);
  out["a"] = s.parameter ? json(tri::TriMask{*s.parameter}.a()) : json(nullptr);
  out["mu"] = nullptr;  // a field of every search report; the triangular family has no μ
  out["value"] = number_or_null(s.value);
  out["bounds"] = {options.lower, options.upper};
  add_search_fields(
      out, s, [](double c) { return c; }, "");
  return out;
}

json tri_sweep_line(const tri::TriBoundary& boundary, const TriEvaluation& e, const TriObjective& target_only) {
  json line = {{"boundary", boundary.name},
               {"type", "triangle"},
               {"degree", boundary.n},
               {"alpha", e.parameter},
               {"a", tri::TriMask{e.parameter}.a()},
               {"status", solvers::to_string(e.summary.status)}};
  if (!e.ok()) {
    line["message"] = e.summary.message;
    return line;
  }
  line["metrics"] = tri_metrics_to_json(tri::tri_net_metrics(e.net, tri::TriMask{e.parameter}));
  if (target_only.target)
    line["rms_target"] = number_or_null(std::sqrt(tri_target_mean_square(e.net, *target_only.target)));
  return line;
}

}  // namespace coons
