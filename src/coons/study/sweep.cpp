#include "sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "coons/io/net_json.h"
#include "coons/io/plot.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/centred_solve.h"
#include "coons/mask/mask_families.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"

namespace coons {

using nlohmann::json;

const char* to_string(SweepParameter parameter) { return parameter == SweepParameter::kMu ? "mu" : "alpha"; }

std::vector<double> linspace(double from, double to, int count) {
  std::vector<double> out(count);
  // from + (to − from)·k/(count − 1), unless (to − from)·(count − 1) overflows (a range near the
  // largest double: the products were infinite, a sweep to 1e308 evaluated μ = inf); then the
  // weighted mean of the ends, which stays between them.
  const bool overflows = !std::isfinite((to - from) * (count - 1));
  for (int k = 0; k < count; ++k) {
    if (count == 1) {
      out[k] = from;
    } else if (!overflows) {
      out[k] = from + (to - from) * k / (count - 1);
    } else {
      const double t = double(k) / (count - 1);
      out[k] = from * (1 - t) + to * t;
    }
    // within [from, to] (either order) and ending on `to` itself: rounding took the last value of
    // a sweep from −0.15 to 0.25 in 7 steps to 0.2500000000000001, beyond the α range, with β < 0
    out[k] = from <= to ? std::clamp(out[k], from, to) : std::clamp(out[k], to, from);
  }
  if (count > 1) out.back() = to;
  return out;
}

MaskFamily sweep_family(SweepParameter parameter, const Boundary& b) {
  if (parameter == SweepParameter::kMu) return [m = b.m, n = b.n](double mu) { return mu_family(m, n, mu); };
  return [](double a) { return alpha_family(a); };
}

std::optional<double> mu_of_alpha(const Boundary& b, std::optional<double> alpha) {
  if (!alpha || b.m != b.n || *alpha < -0.25 || *alpha >= -kAlphaZeroWithinRounding) return std::nullopt;
  return mu_from_alpha(b.n, *alpha);
}

std::vector<SweepRow> run_sweep(const Boundary& b, const std::vector<double>& params, const MaskFamily& family,
                                const solvers::SolverInfo& info, const std::optional<Target>& target,
                                const std::function<void(size_t, size_t)>& progress, std::vector<ControlNet>* nets,
                                const solvers::SolverOptions& options) {
  const ControlNet frame = frame_net(b);
  const int rows = std::max(b.m - 1, 0), cols = std::max(b.n - 1, 0);
  // Masks that reproduce constants (the α and μ families) are solved for the boundary moved to its
  // centre, the nets moved back, as solve_mask_net solves them.
  bool invariant = true;
  for (double p : params) invariant = invariant && family(p).mask.reproduces_constants();
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  ControlNet centred = frame;
  if (invariant) {
    std::vector<Stencil> stencils;  // (the data the members couple to the interior: stencil_problem.h)
    stencils.reserve(params.size());
    for (double p : params) stencils.push_back(alpha_stencil(family(p).mask));
    centre = data_centre(rings_problem(frame, 1), stencils);
    centred.points.rowwise() -= centre;
  }
  const std::vector<Eigen::MatrixX3d> basis = {mask_rhs(centred, Mask9{1, 0, 0}), mask_rhs(centred, Mask9{0, 1, 0}),
                                               mask_rhs(centred, Mask9{0, 0, 1})};
  std::vector<SweepRow> rows_out(params.size());
  std::vector<Eigen::SparseMatrix<double>> matrices;
  std::vector<solvers::LinearSolver::SweepMember> members;
  for (size_t k = 0; k < params.size(); ++k) {
    rows_out[k].parameter = params[k];
    rows_out[k].mask = family(params[k]).mask;
    rows_out[k].summary.solver = info.name;
    solvers::LinearOperator op;
    op.stencil = mask_stencil(rows_out[k].mask, rows, cols);
    members.push_back({op, {rows_out[k].mask.edge_i, rows_out[k].mask.edge_j, rows_out[k].mask.diag}});
  }
  if (info.needs_matrix) {
    matrices.reserve(params.size());
    for (auto& m : members) {
      matrices.push_back(solvers::stencil_matrix(*m.op.stencil));
      m.op.matrix = &matrices.back();
    }
  }
  auto finish_row = [&](size_t k, const ControlNet& net) {
    rows_out[k].metrics = net_metrics(net, rows_out[k].mask);
    if (target) rows_out[k].rms_target = rms_distance(net, *target);
    if (nets) nets->push_back(net);
    if (progress) progress(k + 1, params.size());
  };
  if (rows * cols == 0) {
    for (size_t k = 0; k < params.size(); ++k) finish_row(k, frame);
  } else {
    auto solver = solvers::make_solver(info.name, options);
    solver->sweep(basis, members, [&](size_t k, const Eigen::MatrixX3d& X, const solvers::SolveSummary& s) {
      rows_out[k].summary = s;
      if (!s.ok()) return finish_row(k, frame);
      Eigen::MatrixX3d moved_back = X;
      moved_back.rowwise() += centre;
      // the residual and verdict of the member's system as given, as solve_mask_net reports them
      if (!centre.isZero(0))
        judge_centred_member(info.name, solver->options().tolerance, members[k].op, mask_rhs(frame, rows_out[k].mask),
                             weight_sum(alpha_stencil(rows_out[k].mask).weights), moved_back, rows_out[k].summary);
      if (!rows_out[k].summary.ok()) return finish_row(k, frame);
      finish_row(k, fill_interior(frame, moved_back));
    });
  }
  return rows_out;
}

json sweep_line(const Boundary& b, SweepParameter parameter, const SweepRow& row) {
  const std::string name = to_string(parameter);
  json line = metrics_to_json(row.metrics);
  line[name] = row.parameter;
  if (parameter != SweepParameter::kAlpha) line["alpha"] = row.mask.diag;
  if (row.mask.edge_i == row.mask.edge_j)
    line["beta"] = row.mask.edge_i;
  else
    line["beta_ij"] = {row.mask.edge_i, row.mask.edge_j};
  if (parameter == SweepParameter::kAlpha) {
    const auto mu = mu_of_alpha(b, row.parameter);
    line["mu"] = mu ? json(*mu) : json(nullptr);
  }
  line["status"] = solvers::to_string(row.summary.status);
  if (!row.summary.ok())
    line = json{
        {name, row.parameter}, {"status", solvers::to_string(row.summary.status)}, {"message", row.summary.message}};
  if (row.rms_target && row.summary.ok()) line["rms_target"] = *row.rms_target;
  line["solver"] = summary_to_json(row.summary);
  return line;
}

std::vector<PlotSeries> sweep_series(const std::vector<SweepRow>& rows,
                                     const std::map<std::string, SweepOptimum>& optima) {
  struct Curve {
    const char* name;
    const char* objective;
    double NetMetrics::*field;
  };
  const Curve curves[] = {{"thin plate", "thin_plate", &NetMetrics::thin_plate_energy},
                          {"E3", "e3", &NetMetrics::e3_energy},
                          {"twist", "twist", &NetMetrics::twist_energy},
                          {"Dirichlet", "dirichlet", &NetMetrics::dirichlet_energy}};
  // Each curve divided by its largest value, its minimum marked in its own colour. Curves that
  // are zero up to rounding (below 1e-12 of the largest curve) carry no shape and are left out;
  // when every curve is exactly 0 (a planar bilinear boundary) they are drawn at 0 (there was
  // nothing to plot, and gnuplot failed: "all points y value undefined").
  struct Candidate {
    std::string name;
    std::vector<double> values;
    const SweepOptimum* optimum = nullptr;  // the search's, where there is one
  };
  std::vector<Candidate> candidates;
  for (const Curve& c : curves) {
    std::vector<double> v;
    v.reserve(rows.size());
    for (const auto& r : rows) v.push_back(r.metrics.*(c.field));
    const auto found = optima.find(c.objective);
    candidates.push_back({c.name, std::move(v), found == optima.end() ? nullptr : &found->second});
  }
  if (!rows.empty() && rows[0].rms_target) {
    std::vector<double> v;
    v.reserve(rows.size());
    for (const auto& r : rows) v.push_back(r.rms_target.value_or(0));
    candidates.push_back({"rms to target", std::move(v), nullptr});
  }
  auto largest = [&](const std::vector<double>& values) {
    double top = 0;
    for (size_t k = 0; k < rows.size(); ++k)
      if (rows[k].summary.ok()) top = std::max(top, std::abs(values[k]));
    return top;
  };
  double overall = 0;
  for (const auto& c : candidates) overall = std::max(overall, largest(c.values));
  std::vector<PlotSeries> series;
  for (const Candidate& c : candidates) {
    const double top = overall == 0 ? 1.0 : largest(c.values);
    if (overall > 0 && !(top > 1e-12 * overall)) continue;
    PlotSeries s{c.name, {}, {}, false};
    std::optional<size_t> best;
    for (size_t k = 0; k < rows.size(); ++k) {
      if (!rows[k].summary.ok()) continue;
      s.x.push_back(rows[k].parameter);
      s.y.push_back(c.values[k] / top);
      if (!best || c.values[k] < c.values[*best]) best = k;
    }
    if (!best) continue;
    if (c.optimum && std::isfinite(c.optimum->parameter) && std::isfinite(c.optimum->value)) {
      s.marker_x = {c.optimum->parameter};
      s.marker_y = {c.optimum->value / top};
    } else {
      s.marker_x = {rows[*best].parameter};
      s.marker_y = {c.values[*best] / top};
    }
    series.push_back(std::move(s));
  }
  return series;
}

std::string plot_sweep(const std::string& png, const Boundary& b, SweepParameter parameter,
                       const std::vector<SweepRow>& rows, const std::map<std::string, SweepOptimum>& optima) {
  const std::vector<PlotSeries> series = sweep_series(rows, optima);
  PlotOptions o;
  o.title = fmt::format("{} ({}x{}): energies / their maximum", b.name, b.m, b.n);
  o.xlabel = to_string(parameter);
  o.ylabel = "normalised value";
  o.marker_title = optima.empty() ? "minimum" : "minimum (the search's optimum where searched)";
  return plot_curves(png, series, o);
}

}  // namespace coons
