// The commands on a B-spline boundary file (knots_u, knots_v, degree_spline: docs/formats.md
// "B-spline boundaries"): solve, export and search-alpha hand such files here after reading them.
// The non-uniform α family and the Greville-weighted Coons net (docs/math.md §10).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cad_commands.h"
#include "common.h"
#include "coons/io/write_files.h"
#include "coons/metrics/energies.h"
#include "coons/net/control_net.h"
#include "coons/study/bspline_net.h"
#include "coons/surfaces/sampling.h"
#include "net_request.h"

namespace coons::cli {

//! `coons solve` of a B-spline boundary: the report of bspline_net_report on standard output.
int run_bspline_solve(const std::string& file, const BoundaryFile& input, const NetRequest& request,
                      const GlobalOptions& global, Phases& phases);

//! What `coons export` writes for a B-spline boundary.
struct BSplineExportRequest {
  std::string file, out_dir, prefix;
  int samples = 33;
  bool obj = false, mtx = false, ply = false, vts = false, force = false;
  CadExportRequest cad;  //!< --step, --iges: the solved surface with its knots (cad_commands.h)
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

//! One net of a B-spline boundary for `coons batch`: the report `coons solve` prints (without its
//! timing), the surface, and, when the net was made, its metrics (bspline_metrics).
struct BSplineBatchNet {
  nlohmann::json report;
  BSplineNetOutcome outcome;
  BSplineResolved resolved;
  std::optional<NetMetrics> metrics;
  [[nodiscard]] bool ok() const { return !outcome.summary || outcome.summary->ok(); }
};
BSplineBatchNet bspline_batch_net(const std::string& file, const BoundaryFile& input, const NetRequest& request,
                                  const GlobalOptions& global);
//! The header comment of a B-spline surface's sampled files.
std::string bspline_samples_comment(const std::string& name, int samples);
//! <stem>.surface.obj (the sampled surface) and <stem>.net.obj (the control net), what export writes
//! by default; returns their paths.
std::vector<std::string> write_bspline_objs(OutputSet& out, const std::string& stem, const SurfaceSamples& grid,
                                            const std::string& comment, const ControlNet& net);

}  // namespace coons::cli
