// `coons refit BOUNDARY --degree M N`: the boundary at another degree, refitted from its analytic
// "curves" or elevated exactly; printed, or written to --out.
#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "coons/io/boundary_curves.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/net_json.h"
#include "coons/io/write_files.h"
#include "coons/net/degree_elevation.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/target.h"
#include "registry.h"

namespace coons::cli {

namespace {

struct RefitRequest {
  std::string boundary;
  std::vector<int> degree;  //!< M N
  std::string out;
  double corner_tolerance = 1e-9;
  GlobalOptions global;
};

int run_refit(const RefitRequest& r) {
  const BoundaryFile file = read_input(r.boundary, r.corner_tolerance);
  if (!is_classical(file))  // it writes the four sides only: a second ring or a free grid would be lost
    throw InputError(r.boundary,
                     file.ribbons     ? "ribbons"
                     : file.rings > 1 ? "rings"
                                      : "free",
                     "refit writes a boundary of one data ring; this file's second ring or free grid would be "
                     "lost");
  const Boundary& b = file.boundary;
  if (r.degree.size() != 2 || r.degree[0] < 1 || r.degree[1] < 1 || r.degree[0] > 1000 || r.degree[1] > 1000)
    throw InputError("command line", "--degree", "needs two degrees M N in [1, 1000]");
  const int m = r.degree[0], n = r.degree[1];
  check_memory(r.global, (m + 1.0) * (n + 1.0) * 3 * 8 * 8, fmt::format("a boundary of degree ({}, {})", m, n),
               "command line", "--degree");
  require_new_file(r.out, r.global.force, "--out");
  // What belongs to the shape rather than to its degree is kept: the analytic sides (refit again)
  // and the target (search-alpha --objective target), both checked before they are copied.
  const nlohmann::json source = read_json_file(r.boundary);
  const auto curves = read_boundary_curves(r.boundary);
  (void)target_from_json(source, r.boundary);
  nlohmann::json out;
  if (curves) {
    const FittedBoundary f = fit_boundary_or_throw(*curves, m, n, b.name, r.boundary);
    out = boundary_to_json(f.boundary);
    out["method"] = "refit";
    out["max_deviation"] = f.max_deviation;
  } else if (m >= b.m && n >= b.n) {
    out = boundary_to_json(elevate_boundary(b, m, n));
    out["method"] = "elevated";
    out["max_deviation"] = 0.0;
  } else {
    throw InputError(r.boundary, "curves",
                     fmt::format("degree ({}, {}) is below the boundary's ({}, {}); lowering it needs "
                                 "the analytic sides (a \"curves\" object)",
                                 m, n, b.m, b.n));
  }
  for (const char* key : {"curves", "target"})
    if (source.contains(key)) out[key] = source[key];
  if (r.out.empty()) {
    print_json(out);
    return kExitOk;
  }
  write_file_atomically(r.out, [&](std::ostream& o) { o << dump(out, 2) << '\n'; });
  print_json(nlohmann::json{{"boundary", b.name},
                            {"degree", {m, n}},
                            {"method", out["method"]},
                            {"max_deviation", out["max_deviation"]},
                            {"written", r.out}});
  return kExitOk;
}

}  // namespace

void register_refit(CLI::App& app, Registry& registry) {
  auto r = std::make_shared<RefitRequest>();
  auto* cmd = app.add_subcommand("refit",
                                 "the boundary at another degree: refitted from its analytic \"curves\", "
                                 "or elevated exactly; prints (or writes) a boundary file");
  cmd->add_option("BOUNDARY", r->boundary, "boundary JSON file (docs/formats.md)")->required();
  cmd->add_option("--degree", r->degree, "the new degree M N")->required()->expected(2)->check(int_item());
  cmd->add_option("--out", r->out, "write the boundary file here (default: standard output)");
  cmd->add_flag("--force", r->global.force, "overwrite --out if it exists");
  cmd->add_option("--corner-tolerance", r->corner_tolerance,
                  "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  add_memory_option(*cmd, r->global);
  set_example(*cmd, "coons refit data/boundaries/dome.json --degree 8 8 --out dome8.json");
  registry.add(cmd, [r] { return run_refit(*r); });
}

}  // namespace coons::cli
