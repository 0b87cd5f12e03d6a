// The commands on a B-spline boundary file (knots_u, knots_v, degree_spline: docs/formats.md
// "B-spline boundaries"): solve, export and search-alpha hand such files here after reading them.
// The non-uniform α family and the Greville-weighted Coons net (docs/math.md §10).
#pragma once

#include <string>

#include "common.h"

namespace coons::cli {

//! `coons solve` of a B-spline boundary: the report of bspline_net_report on standard output.
int run_bspline_solve(const std::string& file, const BoundaryFile& input, const NetRequest& request,
                      const GlobalOptions& global, Phases& phases);

//! What `coons export` writes for a B-spline boundary.
struct BSplineExportRequest {
  std::string file, out_dir, prefix;
  int samples = 33;
  bool obj = false, mtx = false, ply = false, vts = false, force = false;
};
int run_bspline_export(const BSplineExportRequest& e, const BoundaryFile& input, const NetRequest& request,
                       const GlobalOptions& global, Phases& phases);

//! The checked method, α and backend of a B-spline request: --mask other than alpha, --mu and
//! hermite-coons are refused (InputErrors naming the option).
struct BSplineResolved {
  Method method = Method::kCoons;
  double alpha = -0.25;
  std::string solver;  //!< backend name (alpha method), auto resolved
  bool picked_automatically = false;
  solvers::SolverOptions options;
};
BSplineResolved resolve_bspline(const NetRequest& request, const BoundaryFile& input, const std::string& source);

}  // namespace coons::cli
