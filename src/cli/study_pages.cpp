// `coons study --html`: one `coons view` page per shape of the study, linked from the report.
#include <fmt/format.h>

#include <set>

#include "coons/config.h"
#include "coons/study/backend_choice.h"
#include "coons/study/bspline_search.h"
#include "coons/study/report_markdown.h"
#include "coons/study/view_data.h"
#include "coons/tri/tri_solve.h"
#include "view_command.h"

namespace coons::cli {

std::string write_study_pages(const StudyResult& result, const std::vector<StudyInput>& inputs,
                              const std::vector<BSplineStudyInput>& bsplines, OutputSet& out,
                              const std::string& three_js, const solvers::SolverInfo* solver) {
  ViewOptions options;
  options.frames = 51;
  options.samples = 25;
  std::vector<std::pair<std::string, std::string>> links;  // (name, relative path)
  std::set<std::string> used;
  auto publish = [&](std::string stem, ViewPage page) {
    for (int k = 2; used.count(stem); ++k) stem = fmt::format("{}-{}", stem, k);
    used.insert(stem);
    page.generator = std::string("coons ") + COONS_VERSION;
    const std::string file = "pages/" + stem + ".html";
    const std::string html = view_page_html(page, three_js);
    out.write(file, [&](std::ostream& o) { o << html; });
    links.emplace_back(page.title, file);
  };
  const std::vector<std::string> stems = shape_file_stems(result);
  for (size_t k = 0; k < result.shapes.size(); ++k) {
    const ShapeEntry& shape = result.shapes[k];
    ViewPage page;
    page.title = shape.boundary.name;
    const solvers::SolverInfo& backend = search_backend(solver, shape.boundary, false);
    page.sliders.push_back(alpha_view_slider(shape.boundary, options, backend, -0.25));
    for (const StudyInput& in : inputs)
      if (in.file == shape.file && in.two_rings && in.two_rings->net.m == shape.boundary.m &&
          in.two_rings->net.n == shape.boundary.n)
        page.sliders.push_back(weight_view_slider(*in.two_rings, options, weight_search_backend(solver), 1.0));
    for (ViewSlider& s : page.sliders) open_at_thin_plate_optimum(s);
    page.subtitle = fmt::format("degree ({}, {}), from the α study", shape.boundary.m, shape.boundary.n);
    publish(stems[k], std::move(page));
  }
  for (const TriStudyEntry& t : result.triangles) {
    ViewPage page;
    page.title = t.boundary.name;
    ViewOptions tri_options = options;
    tri_options.lower = tri_options.upper = 0;  // the search's default bounds
    page.sliders.push_back(tri_view_slider(t.boundary, tri_options, tri::default_tri_solver(), -1.0 / 6.0));
    open_at_thin_plate_optimum(page.sliders[0]);
    page.subtitle = fmt::format("triangular net of degree {}, from the α study", t.boundary.n);
    publish(safe_file_stem(t.boundary.name), std::move(page));
  }
  for (const BSplineStudyInput& b : bsplines) {
    ViewPage page;
    page.title = b.name;
    ViewOptions bspline_options = options;
    bspline_options.upper = bspline_definite_upper(b.sides.compatible);
    const std::string backend = weight_search_backend(solver).name;  // the requested one, else the default definite one
    page.sliders.push_back(bspline_view_slider(b.sides.compatible, bspline_options, backend, -0.25));
    open_at_thin_plate_optimum(page.sliders[0]);
    page.subtitle = fmt::format("B-spline net at its own knots, from the study, solver {}", backend);
    publish(safe_file_stem(b.name), std::move(page));
  }
  std::string md =
      "\n## Pages\n\nOne page per shape to open in a browser (`coons view`: the surface with reflection "
      "lines, its net, a slider over precomputed nets, the energy curves with the optima):\n\n";
  for (const auto& [name, file] : links) md += fmt::format("- [{}]({})\n", name, file);
  return md;
}

}  // namespace coons::cli
