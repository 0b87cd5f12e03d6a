// `coons view BOUNDARY --out PAGE.html`: one self-contained HTML page (three.js inlined) with the
// surface shaded with reflection lines, its control net, an α slider over precomputed nets and
// the energy curves with the optima (coons/study/view_data.h, coons/io/view_page.h); a boundary
// with ribbons also gets the C1 family's weight slider, a triangular boundary the slider of c, a
// B-spline boundary the slider of its non-uniform α family.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "coons/config.h"
#include "coons/io/boundary_curves.h"
#include "coons/io/input_error.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/io/view_page.h"
#include "coons/io/write_files.h"
#include "coons/net/degree_elevation.h"
#include "coons/study/backend_choice.h"
#include "coons/study/bspline_net.h"
#include "coons/study/bspline_search.h"
#include "coons/study/tri_search.h"
#include "coons/study/two_ring_problem.h"
#include "coons/study/view_data.h"
#include "coons/tri/tri_solve.h"
#include "registry.h"
#include "search_inputs.h"
#include "view_command.h"

namespace coons::cli {

namespace {

struct ViewRequest {
  std::string boundary;
  std::string out;
  int alphas = 101;
  int samples = 33;
  double from = -0.25, to = 0.25;
  std::optional<double> alpha;
  std::vector<int> degree;
  std::string three_js = COONS_THREE_JS_PATH;
  std::string solver = "auto";
  double corner_tolerance = 1e-9;
  GlobalOptions global;
  CLI::Option *from_option = nullptr, *to_option = nullptr;
};

}  // namespace

std::string read_three_js(const std::string& path) {
  if (path.empty())
    throw InputError("command line", "--three-js",
                     "three.js was not found when coons was built: install the Debian package libjs-three "
                     "(then reconfigure) or give --three-js PATH/three.min.js");
  // A device or a pipe would be read without end (/dev/zero grew to 13 GB), and a regular file far
  // larger than three.js (about 0.6 MB) is not it: both refused before reading.
  constexpr std::uintmax_t kMaxThreeJsBytes = std::uintmax_t{64} << 20;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, "--three-js",
                     std::filesystem::exists(path, ec) ? "is not a regular file (three.min.js is one)"
                                                       : "cannot open three.js (Debian package libjs-three)");
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec); !ec && size > kMaxThreeJsBytes)
    throw InputError(
        path, "--three-js",
        fmt::format("{} bytes, more than the {} a three.js could be: this is not three.js", size, kMaxThreeJsBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "--three-js", "cannot open three.js (Debian package libjs-three)");
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().find("REVISION") == std::string::npos)
    throw InputError(path, "--three-js", "this is not three.js (no REVISION in it)");
  return text.str();
}

namespace {

// The boundary at the degree asked for: refitted from its analytic sides, or elevated exactly.
Boundary at_degree(const Boundary& b, const std::vector<int>& degree, const std::string& path) {
  if (degree.empty()) return b;
  if (degree.size() != 2 || degree[0] < 1 || degree[1] < 1 || degree[0] > 200 || degree[1] > 200)
    throw InputError("command line", "--degree", "needs two degrees M N in [1, 200]");
  const int m = degree[0], n = degree[1];
  if (const auto curves = read_boundary_curves(path))
    return fit_boundary_or_throw(*curves, m, n, b.name, path).boundary;
  if (m >= b.m && n >= b.n) return elevate_boundary(b, m, n);
  throw InputError(path, "curves",
                   fmt::format("degree ({}, {}) is below the boundary's ({}, {}); lowering it needs the analytic "
                               "sides (a \"curves\" object)",
                               m, n, b.m, b.n));
}

// The triangle's slider (c of the triangular family; `--degree`, `--from`/`--to` do not apply).
ViewSlider triangle_slider(const ViewRequest& r, const ViewOptions& options, std::string* solver_name,
                           std::string* title, nlohmann::json* degree) {
  if (!r.degree.empty()) throw InputError("command line", "--degree", "does not apply to a triangular boundary");
  for (const auto& [option, name] : {std::pair{r.from_option, "--from"}, std::pair{r.to_option, "--to"}})
    if (option && option->count() > 0)
      throw InputError("command line", name,
                       "does not apply to a triangular boundary (its c slider spans the search's default bounds)");
  TriBoundaryReadOptions read;
  read.corner_tolerance = r.corner_tolerance;
  const tri::TriBoundary t = read_tri_boundary_file(r.boundary, read);
  const solvers::SolverInfo* solver = &tri::default_tri_solver();
  if (r.solver != "auto") {
    solver = solver_from_name(r.solver);
    const tri::TriBackendCheck check = tri::check_tri_backend(*solver, tri::TriMask{-1.0 / 6.0});
    if (!check.applicable) throw InputError("command line", "--solver", check.reason);
  }
  *solver_name = solver->name;
  *title = t.name.empty() ? r.boundary : t.name;
  *degree = t.n;
  ViewOptions tri_options = options;
  tri_options.lower = tri_options.upper = 0;  // the search's default bounds
  if (const auto [lo, hi] = default_tri_bounds(t.n); r.alpha && !(*r.alpha >= lo && *r.alpha <= hi))
    throw InputError("command line", "--alpha",
                     fmt::format("must lie in [{}, {}], the c range of a triangle of degree {}", lo, hi, t.n));
  ViewSlider slider = tri_view_slider(t, tri_options, *solver, r.alpha.value_or(-1.0 / 6.0));
  if (!r.alpha) open_at_thin_plate_optimum(slider);
  return slider;
}

// The page's nets and samples (m, n the net's degree) against --max-memory.
void check_page_memory(const ViewRequest& r, int m, int n) {
  const double points = (m + 1.0) * (n + 1.0) + 2.0 * r.samples * r.samples;
  check_memory(r.global, (2 * r.alphas + 12.0) * points * 3 * (8 + 14) + 2e6,
               fmt::format("a page of {} nets of degree ({}, {})", r.alphas, m, n), r.boundary, "degree");
}

// The slider of a B-spline boundary (the non-uniform α family over [--from, --to], --to at most
// where its system stops being definite, by default that end; `--degree` does not apply).
ViewSlider bspline_slider(const ViewRequest& r, ViewOptions options, const BSplineInput& in, std::string* solver_name) {
  if (!r.degree.empty())
    throw InputError("command line", "--degree",
                     "does not apply to a B-spline boundary (its net is the B-spline surface's, at its own knots)");
  const double definite_upper = bspline_definite_upper(in.compatible);
  const std::string definite = fmt::format(
      "the non-uniform system of this B-spline boundary is definite for alpha in [-0.25, {}] only (it can be "
      "singular above)",
      definite_upper);
  if (r.to_option->count() == 0) {
    options.upper = definite_upper;
    if (!(options.lower < definite_upper))
      throw InputError("command line", "--from", fmt::format("must lie below {}: {}", definite_upper, definite));
  } else if (options.upper > definite_upper) {
    throw InputError("command line", "--to", definite);
  }
  if (const ViewOptionsProblem problem = options_problem(options); problem.field != ViewOptionsField::kNone)
    throw InputError("command line", "--from/--to", problem.reason);
  if (r.alpha && !(*r.alpha >= options.lower && *r.alpha <= options.upper))
    throw InputError("command line", "--alpha", fmt::format("must lie in [{}, {}]", options.lower, options.upper));
  const solvers::SolverInfo* requested = require_matrix_backend(solver_from_name(r.solver), kBSplineNeedsMatrix);
  *solver_name = weight_search_backend(requested).name;  // the requested one, else the default definite one
  ViewSlider slider = bspline_view_slider(in.compatible, options, *solver_name,
                                          r.alpha.value_or(std::clamp(-0.25, options.lower, options.upper)));
  if (!r.alpha) open_at_thin_plate_optimum(slider);
  return slider;
}

int run_view(const ViewRequest& r) {
  Phases phases("view");
  phases.start("read");
  require_new_output(r.out, r.global.force, "--out");
  const std::filesystem::path parent = std::filesystem::path(r.out).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw InputError("command line", "--out",
                     fmt::format(std::filesystem::exists(parent) ? "'{}' exists and is not a folder"
                                                                 : "the folder '{}' does not exist",
                                 parent.string()));
  const std::string three_js = read_three_js(r.three_js);
  ViewOptions options;
  options.frames = r.alphas;
  options.samples = r.samples;
  options.lower = r.from;
  options.upper = r.to;
  switch (const ViewOptionsProblem problem = options_problem(options); problem.field) {
    case ViewOptionsField::kNone:
      break;
    case ViewOptionsField::kFrames:
      throw InputError("command line", "--alphas", problem.reason);
    case ViewOptionsField::kSamples:
      throw InputError("command line", "--samples", problem.reason);
    case ViewOptionsField::kInterval:  // a B-spline boundary's range ends at its own U: checked below
      break;
    case ViewOptionsField::kObjectives:
      throw std::logic_error("view: " + problem.reason);  // the objectives are the page's own
  }
  ViewPage page;
  page.generator = std::string("coons ") + COONS_VERSION;
  std::string solver_name;
  nlohmann::json degree;  // [m, n], or n for a triangle
  if (is_triangle_file(r.boundary)) {
    phases.start("solve");
    page.sliders.push_back(triangle_slider(r, options, &solver_name, &page.title, &degree));
    page.subtitle =
        fmt::format("triangular net, {} values of c, solver {}", page.sliders[0].frames.size(), solver_name);
  } else if (const BoundaryFile file = read_input(r.boundary, r.corner_tolerance, true); file.bspline) {
    const ControlNet frame = bspline_frame(file.bspline->compatible);
    degree = {frame.m, frame.n};
    check_page_memory(r, frame.m, frame.n);
    phases.start("solve");
    page.sliders.push_back(bspline_slider(r, options, *file.bspline, &solver_name));
    const ViewSlider& alpha = page.sliders[0];
    page.title = file.boundary.name.empty() ? r.boundary : file.boundary.name;
    page.subtitle = fmt::format("B-spline net of {} by {} control points, {} values of α in [{}, {}], solver {}",
                                frame.m + 1, frame.n + 1, alpha.frames.size(), alpha.lower, alpha.upper, solver_name);
  } else {
    if (const ViewOptionsProblem problem = options_problem(options); problem.field == ViewOptionsField::kInterval)
      throw InputError("command line", "--from/--to", problem.reason);
    const Boundary b = at_degree(file.boundary, r.degree, r.boundary);
    degree = {b.m, b.n};
    if (r.alpha && !(*r.alpha >= r.from && *r.alpha <= r.to))
      throw InputError("command line", "--alpha", fmt::format("must lie in [{}, {}]", r.from, r.to));
    require_search_backend(solver_from_name(r.solver), b, false);
    const solvers::SolverInfo& solver = search_backend(solver_from_name(r.solver), b, false);
    solver_name = solver.name;
    check_page_memory(r, b.m, b.n);
    // the C1 family's slider where the file has two data rings (ribbons) and keeps its degree
    const TwoRingProblem two = two_ring_problem(file);
    const bool weight = two.problem && (b.m == file.boundary.m && b.n == file.boundary.n);

    phases.start("solve");
    // (without --alpha the Coons net's -0.25, or the nearest end of --from/--to: the page opened
    // on a frame outside its slider)
    page.sliders.push_back(alpha_view_slider(b, options, solver, r.alpha.value_or(std::clamp(-0.25, r.from, r.to))));
    if (!r.alpha) open_at_thin_plate_optimum(page.sliders[0]);
    if (weight) {
      const solvers::SolverInfo& weight_solver = weight_search_backend(solver_from_name(r.solver));
      page.sliders.push_back(weight_view_slider(*two.problem, options, weight_solver, 1.0));
      open_at_thin_plate_optimum(page.sliders[1]);
    }
    page.title = b.name.empty() ? r.boundary : b.name;
    page.subtitle =
        fmt::format("degree ({}, {}), {} values of α in [{}, {}]{}, solver {}", b.m, b.n, page.sliders[0].frames.size(),
                    r.from, r.to, weight ? ", and the C1 weight w on the ribbons" : "", solver.name);
  }
  if (std::string why; !page.is_valid(&why)) throw std::logic_error("view page: " + why);

  phases.start("write");
  const std::string html = view_page_html(page, three_js);
  OutputSet out(parent.empty() ? "." : parent.string(), "--out");
  out.write_path(r.out, [&](std::ostream& o) { o << html; });
  const ViewSlider& alpha = page.sliders.front();
  nlohmann::json summary = {{"boundary", page.title},         {"degree", degree},     {"page", r.out},
                            {"frames", alpha.frames.size()},  {"samples", r.samples}, {"bytes", html.size()},
                            {"initial_alpha", alpha.initial}, {"solver", solver_name}};
  for (const ViewSlider& s : page.sliders) {
    nlohmann::json optima = nlohmann::json::object();
    for (const ViewCurve& c : s.curves)
      optima[c.name] = c.optimum ? nlohmann::json(*c.optimum) : nlohmann::json(c.status);
    summary[s.parameter == "alpha" ? "optima" : s.parameter + "_optima"] = optima;
  }
  summary["sliders"] = nlohmann::json::array();
  for (const ViewSlider& s : page.sliders) summary["sliders"].push_back(s.parameter);
  summary["timing"] = phases.timing();
  out.publish([&] { print_json(summary); });
  // The page stands without the optima of searches whose solves failed; the command says so, as
  // search-alpha does for one (exit 3).
  std::vector<std::string> failed;
  for (const ViewSlider& s : page.sliders)
    for (const ViewCurve& c : s.curves)
      if (!c.optimum && (c.status == "solver_failed" || c.status == "failed_region"))
        failed.push_back(fmt::format("{} ({})", c.name, c.status));
  if (failed.empty()) return kExitOk;
  std::cerr << fmt::format("error: {}: solver: {} search failed for {}; the page is written without their optima\n",
                           r.boundary, solver_name, fmt::join(failed, ", "));
  return kExitSolverFailed;
}

}  // namespace

void register_view(CLI::App& app, Registry& registry) {
  auto r = std::make_shared<ViewRequest>();
  auto* cmd = app.add_subcommand("view",
                                 "one self-contained HTML page: the surface with reflection lines, its net, an "
                                 "alpha slider and the energy curves with the optima");
  cmd->add_option("BOUNDARY", r->boundary, "boundary JSON file (docs/formats.md)")->required();
  cmd->add_option("--out", r->out, "the HTML file to write")->required();
  cmd->add_option("--alphas", r->alphas, "alpha values on an even grid (the optima are added)")->capture_default_str();
  cmd->add_option("--samples", r->samples, "surface samples per direction")->capture_default_str();
  r->from_option =
      cmd->add_option("--from", r->from, "smallest alpha")->transform(fold_negative_zero())->capture_default_str();
  r->to_option =
      cmd->add_option("--to", r->to, "largest alpha")->transform(fold_negative_zero())->capture_default_str();
  cmd->add_option("--alpha", r->alpha, "the alpha shown first (default: the thin-plate optimum, else -0.25)")
      ->transform(fold_negative_zero());
  cmd->add_option("--degree", r->degree, "M N: refit (or elevate) the boundary to this degree first")->expected(2);
  cmd->add_option("--three-js", r->three_js, "three.min.js to inline (Debian libjs-three)")->capture_default_str();
  cmd->add_option("--corner-tolerance", r->corner_tolerance,
                  "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  cmd->add_flag("--force", r->global.force, "overwrite the page");
  add_solver_option(*cmd, r->solver);
  add_memory_option(*cmd, r->global);
  set_example(*cmd, "coons view data/boundaries/dome.json --out dome.html   (then open dome.html#alpha=-0.2)");
  registry.add(cmd, [r] { return run_view(*r); });
}

}  // namespace coons::cli
