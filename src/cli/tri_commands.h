// The commands on triangular boundaries ({"type": "triangle", ...}, docs/formats.md): solve,
// export, search-alpha and sweep detect such a file at the top of their run function
// (is_triangle_file) and hand the options they parsed to the functions here; everything
// triangular of the command line lives in tri_commands.cpp.
#pragma once

#include <optional>
#include <string>

#include "common.h"
#include "net_request.h"

namespace coons::cli {

//! `coons solve T.json --alpha c [--solver NAME]`.
int run_tri_solve(const std::string& path, const NetRequest& net, const GlobalOptions& global);

struct TriExportArgs {
  std::string boundary;
  const NetRequest* net = nullptr;
  const GlobalOptions* global = nullptr;
  std::string out_dir, prefix;
  int samples = 33;
  bool obj = false, mtx = false, ply = false, vtu = false;
};
//! `coons export T.json`: PREFIX.surface.obj, PREFIX.net.obj, PREFIX.surface.ply,
//! PREFIX.surface.vtu (and PREFIX.A.mtx, PREFIX.B.mtx with --mtx).
int run_tri_export(const TriExportArgs& args);

struct TriSearchArgs {
  std::string boundary, objective, solver;
  std::optional<double> lower, upper;
  int scan_points = 9, samples = 41;
  double corner_tolerance = 1e-9;
  const GlobalOptions* global = nullptr;
  std::string rejected;        //!< an option given that does not apply to triangles (empty: none)
  bool samples_given = false;  //!< --samples was given (it applies to a target term only)
};
//! `coons search-alpha T.json --objective NAME`: the search over c.
int run_tri_search(const TriSearchArgs& args);

struct TriSweepArgs {
  std::string boundary, solver, out_dir;
  std::optional<double> from, to;
  int count = 51, samples = 41;
  double corner_tolerance = 1e-9;
  const GlobalOptions* global = nullptr;
  std::string rejected;        //!< an option given that does not apply to triangles (empty: none)
  bool samples_given = false;  //!< --samples on the command line (refused when the file has no target)
};
//! `coons sweep T.json`: NAME.sweep-c.jsonl, one line per c.
int run_tri_sweep(const TriSweepArgs& args);

}  // namespace coons::cli
