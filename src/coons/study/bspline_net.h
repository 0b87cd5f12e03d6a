// One net of a B-spline boundary (docs/math.md §10, docs/formats.md "B-spline boundaries") and its
// report: --method coons is the Greville-weighted discrete Coons net (greville_coons_surface),
// --method alpha solves the non-uniform mask family (nonuniform_mask.h) with any backend that
// takes an assembled matrix. The result is a tensor B-spline surface on the compatible knots.
// Metrics are the exact energies of that surface (bspline_energy.h), the index-space discrete
// energies of its net and the residual of the non-uniform mask equations.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "coons/io/bspline_boundary_io.h"
#include "coons/mask/nonuniform_mask.h"
#include "coons/metrics/energies.h"
#include "coons/study/net_report.h"
#include "coons/surfaces/bspline_surface.h"
#include "solvers/linear_solver.h"

namespace coons {

//! The Greville abscissae on [0, 1] of the compatible sides (bottom's knots in u, left's in v).
GrevilleGrid greville_grid(const BSplineBoundary& compatible);

//! The surface on the compatible knots with `net` as its control net.
BSplineSurface bspline_surface_on(const BSplineBoundary& compatible, ControlNet net);

//! The frame net of compatible sides (interior zero): bottom, top, left, right on its frame.
ControlNet bspline_frame(const BSplineBoundary& compatible);

//! The middle of the bounding box of the sides' control points, and the sides moved by `by`: the
//! nets are solved and measured in the frame centred there. A boundary far from the origin lost
//! the shape's digits to the offset: at 1e12 its e3 came out 1.5 % off and the search's α* moved.
Eigen::RowVector3d bspline_centre(const BSplineBoundary& compatible);
BSplineBoundary bspline_translated(const BSplineBoundary& compatible, const Eigen::RowVector3d& by);

struct BSplineNetOutcome {
  BSplineSurface surface;                        //!< net and knots (frame only when the solve failed)
  BSplineSurface local;                          //!< the same net moved by −bspline_centre (metrics)
  std::optional<solvers::SolveSummary> summary;  //!< the alpha method only
};

//! kCoons: greville_coons_surface; kAlpha: the non-uniform α net solved with `solver` (required
//! then). kHermiteCoons has no B-spline form: the Coons net is returned (callers refuse it first).
BSplineNetOutcome make_bspline_net(const BSplineBoundary& compatible, NetMethod method, double alpha,
                                   solvers::LinearSolver* solver);

//! The backend `--solver auto` uses: a sparse Cholesky (cholmod when built, else eigen-ldlt) for
//! α ∈ [−1/4, 0], where the system is positive definite, else eigen-lu.
std::string auto_bspline_solver(double alpha);

//! Every metric of the solve report for a B-spline net (all of them invariant under translation:
//! pass BSplineNetOutcome::local).
NetMetrics bspline_metrics(const BSplineSurface& surface, double alpha);

//! The "bspline" block of a report: degree_spline, knots_u, knots_v, greville_u, greville_v and
//! "compatibility" (one note per side that was changed; an empty list when none was).
nlohmann::json bspline_block(const BSplineSurface& surface, const BSplineInput& input);

//! The solve report of a B-spline boundary (the fields of net_report plus "bspline"). `alpha` is
//! −1/4 for kCoons. With `with_net` false a successful net is left out for the caller to write.
//! `metrics`, when given, are bspline_metrics of the net, already computed by the caller.
nlohmann::json bspline_net_report(const std::string& name, const BSplineInput& input, NetMethod method, double alpha,
                                  const BSplineNetOutcome& outcome, bool solver_picked_automatically,
                                  bool with_net = true, const NetMetrics* metrics = nullptr);

}  // namespace coons
