#include "coons/study/bspline_net.h"

#include <algorithm>
#include <utility>

#include "coons/io/net_json.h"
#include "coons/mask/stencil_problem.h"
#include "coons/study/net_report.h"
#include "coons/surfaces/bspline_energy.h"
#include "solvers/registry.h"

namespace coons {

using nlohmann::json;

GrevilleGrid greville_grid(const BSplineBoundary& b) {
  return {greville_abscissae(reparametrised(b.bottom, 0.0, 1.0)), greville_abscissae(reparametrised(b.left, 0.0, 1.0))};
}

BSplineSurface bspline_surface_on(const BSplineBoundary& b, ControlNet net) {
  BSplineSurface s;
  s.degree_u = b.bottom.degree;
  s.degree_v = b.left.degree;
  s.knots_u = reparametrised(b.bottom, 0.0, 1.0).knots;
  s.knots_v = reparametrised(b.left, 0.0, 1.0).knots;
  s.net = std::move(net);
  return s;
}

ControlNet bspline_frame(const BSplineBoundary& b) {
  Boundary frame;
  frame.m = b.bottom.count() - 1;
  frame.n = b.left.count() - 1;
  frame.bottom = b.bottom.points;
  frame.top = b.top.points;
  frame.left = b.left.points;
  frame.right = b.right.points;
  return frame_net(frame);
}

std::string auto_bspline_solver(double alpha) {
  return solvers::default_matrix_solver(alpha >= -0.25 && alpha <= 0.0).name;
}

Eigen::RowVector3d bspline_centre(const BSplineBoundary& b) {
  Eigen::RowVector3d lo = b.bottom.points.row(0), hi = lo;
  for (const BSplineCurve* side : {&b.bottom, &b.top, &b.left, &b.right}) {
    lo = lo.cwiseMin(side->points.colwise().minCoeff());
    hi = hi.cwiseMax(side->points.colwise().maxCoeff());
  }
  return 0.5 * lo + 0.5 * hi;
}

BSplineBoundary bspline_translated(const BSplineBoundary& b, const Eigen::RowVector3d& by) {
  BSplineBoundary out = b;
  for (BSplineCurve* side : {&out.bottom, &out.top, &out.left, &out.right}) side->points.rowwise() += by;
  return out;
}

BSplineNetOutcome make_bspline_net(const BSplineBoundary& b, NetMethod method, double alpha,
                                   solvers::LinearSolver* solver) {
  // solved in the frame centred on the boundary (every mask row sums to 1: the net moves with it)
  const Eigen::RowVector3d centre = bspline_centre(b);
  const BSplineBoundary local = bspline_translated(b, -centre);
  BSplineNetOutcome out;
  if (method != NetMethod::kAlpha || solver == nullptr) {
    out.local = greville_coons_surface(local);
  } else {
    // a singular system (the threshold of the stencil path's check at the input edge) is refused,
    // not solved into a net of rounding noise
    NonUniformSolveResult result = solve_nonuniform_mask_net(bspline_frame(local), greville_grid(local), alpha, *solver,
                                                             false, ProblemCheckOptions{}.singular_tolerance);
    out.local = bspline_surface_on(local, std::move(result.net));
    out.summary = std::move(result.summary);
  }
  // in the boundary's coordinates: the closed form as it stands (its points there are as good as
  // the local ones moved back), the solved net's interior moved back into its own frame
  if (method != NetMethod::kAlpha || solver == nullptr) {
    out.surface = greville_coons_surface(b);
    return out;
  }
  out.surface = out.local;
  out.surface.net = bspline_frame(b);
  for (int i = 1; i < out.surface.net.m; ++i)
    for (int j = 1; j < out.surface.net.n; ++j) out.surface.net.at(i, j) = out.local.net.at(i, j) + centre;
  return out;
}

NetMetrics bspline_metrics(const BSplineSurface& s, double alpha) {
  NetMetrics out;
  out.twist_energy = bspline_combined_energy(s, bspline_twist_terms());
  out.thin_plate_energy = bspline_combined_energy(s, bspline_thin_plate_terms());
  out.dirichlet_energy = bspline_combined_energy(s, bspline_dirichlet_terms());
  out.e3_energy = bspline_combined_energy(s, bspline_e3_terms());
  out.discrete_twist_energy = discrete_twist_energy(s.net);
  out.discrete_dirichlet_energy = discrete_dirichlet_energy(s.net);
  const GrevilleGrid grid{
      greville_abscissae(BSplineCurve(s.degree_u, s.knots_u, Eigen::MatrixX3d::Zero(s.net.m + 1, 3))),
      greville_abscissae(BSplineCurve(s.degree_v, s.knots_v, Eigen::MatrixX3d::Zero(s.net.n + 1, 3)))};
  out.mask_residual = nonuniform_mask_residual(s.net, grid, alpha);
  return out;
}

namespace {

json vector_json(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

}  // namespace

json bspline_block(const BSplineSurface& s, const BSplineInput& input) {
  json block;
  block["degree_spline"] = {s.degree_u, s.degree_v};
  block["knots_u"] = vector_json(s.knots_u);
  block["knots_v"] = vector_json(s.knots_v);
  const GrevilleGrid grid = greville_grid(input.compatible);
  block["greville_u"] = vector_json(grid.xi);
  block["greville_v"] = vector_json(grid.eta);
  json notes = json::array();
  for (const CompatibilityNote& note : input.notes)
    notes.push_back(
        {{"side", note.side}, {"degree_raised_by", note.degree_raised_by}, {"knots_inserted", note.knots_inserted}});
  block["compatibility"] = notes;
  return block;
}

json bspline_net_report(const std::string& name, const BSplineInput& input, NetMethod method, double alpha,
                        const BSplineNetOutcome& outcome, bool solver_picked_automatically, bool with_net,
                        const NetMetrics* metrics) {
  const BSplineSurface& s = outcome.surface;
  json report;
  report["boundary"] = name;
  report["degree"] = {s.net.m, s.net.n};
  report["method"] = to_string(method);
  report["mask"] = "alpha";
  report["alpha"] = alpha;
  report["beta"] = nullptr;  // the non-uniform weights differ from point to point
  report["mu"] = nullptr;
  report["rings"] = 1;
  report["free_points"] = std::max(s.net.m - 1, 0) * std::max(s.net.n - 1, 0);
  report["solver"] = solver_block(outcome.summary, solver_picked_automatically);
  report["bspline"] = bspline_block(s, input);
  const bool ok = !outcome.summary || outcome.summary->ok();
  if (!ok)
    report["net"] = nullptr;
  else if (with_net)
    report["net"] = net_to_json(s.net);
  report["metrics"] = ok ? metrics_to_json(metrics ? *metrics : bspline_metrics(outcome.local, alpha)) : json(nullptr);
  return report;
}

}  // namespace coons
