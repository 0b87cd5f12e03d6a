#include "coons/study/study_json.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/study/bspline_search.h"
#include "coons/study/tri_search.h"

namespace coons {

using nlohmann::json;

namespace {

// ---- numbers, matrices, enums -------------------------------------------------------------------

json num(double x) {
  if (std::isfinite(x)) return x;
  if (std::isnan(x)) return "nan";
  return x > 0 ? "inf" : "-inf";
}

double num_of(const json& j) {
  if (j.is_number()) return j.get<double>();
  const auto s = j.get<std::string>();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  throw std::invalid_argument("'" + s + "' is not a number");
}

// Integers through json_integer, never get<int>: a float such as 1e300 converted to an int is
// undefined behaviour. Anything but an integer in [lo, hi] is malformed, like every other error here.
std::int64_t integer_of(const json& j, const char* what, std::int64_t lo, std::int64_t hi) {
  try {
    return json_integer(j, "", what, lo, hi);
  } catch (const InputError& e) {
    throw std::invalid_argument(e.field() + ": " + e.reason());
  }
}
int int_of(const json& j, const char* what, int lo = 0) {
  try {
    return json_int(j, "", what, lo);
  } catch (const InputError& e) {
    throw std::invalid_argument(e.field() + ": " + e.reason());
  }
}

json opt(const std::optional<double>& x) { return x ? num(*x) : json(nullptr); }
std::optional<double> opt_of(const json& j) {
  if (j.is_null()) return std::nullopt;
  return num_of(j);
}

json matrix(const Eigen::MatrixX3d& M) {
  json rows = json::array();
  for (Eigen::Index r = 0; r < M.rows(); ++r) rows.push_back({num(M(r, 0)), num(M(r, 1)), num(M(r, 2))});
  return rows;
}
Eigen::MatrixX3d matrix_of(const json& j) {
  if (!j.is_array()) throw std::invalid_argument("a list of points is not a list");
  Eigen::MatrixX3d M(Eigen::Index(j.size()), 3);
  for (size_t r = 0; r < j.size(); ++r) {
    if (!j[r].is_array() || j[r].size() != 3) throw std::invalid_argument("a point has not 3 coordinates");
    for (int c = 0; c < 3; ++c) M(Eigen::Index(r), c) = num_of(j[r][size_t(c)]);
  }
  return M;
}

json pairs(const std::vector<std::pair<double, double>>& v) {
  json out = json::array();
  for (const auto& [a, b] : v) out.push_back({num(a), num(b)});
  return out;
}
std::vector<std::pair<double, double>> pairs_of(const json& j) {
  std::vector<std::pair<double, double>> out;
  for (const json& p : j) out.emplace_back(num_of(p.at(0)), num_of(p.at(1)));
  return out;
}

template <typename E>
E enum_of(const std::string& s, E last) {
  for (int k = 0; k <= int(last); ++k)
    if (s == to_string(E(k))) return E(k);
  throw std::invalid_argument("unknown status '" + s + "'");
}

// ---- value types --------------------------------------------------------------------------------

json summary(const AlphaSearchSummary& s) {
  return {{"status", to_string(s.status)},
          {"message", s.message},
          {"parameter", opt(s.parameter)},
          {"value", num(s.value)},
          {"flat", s.flat},
          {"at_bound", s.at_bound},
          {"local_minima", s.local_minima},
          {"evaluations", s.evaluations},
          {"solves", s.solves},
          {"scan", pairs(s.scan)},
          {"failed_evaluations", s.failed_evaluations},
          {"first_failure", to_string(s.first_failure)},
          {"failed_intervals", pairs(s.failed_intervals)},
          {"seconds", num(s.seconds)},
          {"ceres_report", s.ceres_report},
          {"evaluator", s.evaluator}};
}
AlphaSearchSummary summary_of(const json& j) {
  AlphaSearchSummary s;
  s.status = enum_of(j.at("status").get<std::string>(), SearchStatus::kNotApplicable);
  s.message = j.at("message").get<std::string>();
  s.parameter = opt_of(j.at("parameter"));
  s.value = num_of(j.at("value"));
  s.flat = j.at("flat").get<bool>();
  s.at_bound = j.at("at_bound").get<bool>();
  s.local_minima = int_of(j.at("local_minima"), "local_minima");
  s.evaluations = int_of(j.at("evaluations"), "evaluations");
  s.solves = int_of(j.at("solves"), "solves");
  s.scan = pairs_of(j.at("scan"));
  s.failed_evaluations = int_of(j.at("failed_evaluations"), "failed_evaluations");
  s.first_failure = enum_of(j.at("first_failure").get<std::string>(), solvers::SolveStatus::kFailure);
  s.failed_intervals = pairs_of(j.at("failed_intervals"));
  s.seconds = num_of(j.at("seconds"));
  s.ceres_report = j.at("ceres_report").get<std::string>();
  s.evaluator = j.at("evaluator").get<std::string>();
  return s;
}

// What a search can have written (the shard key covers a part's inputs, not its results: an edited
// c* of 5, a value "nan" or -3, "flat" beside a number and "at_bound" on an interior point were
// merged into the report as they stood). `lower`, `upper`: the bounds the study searched.
void check_search(const AlphaSearchSummary& s, double lower, double upper, const std::string& what) {
  const auto bad = [&](const std::string& why) { throw std::invalid_argument(what + ": " + why); };
  if (s.flat != (s.status == SearchStatus::kFlat))
    bad(fmt::format("flat is {} but the status is '{}'", s.flat, to_string(s.status)));
  if (!s.parameter) {
    if (s.at_bound) bad("at_bound without an optimum");
    return;
  }
  if (s.flat) bad(fmt::format("a flat objective has no optimum, yet one is given ({})", *s.parameter));
  const double p = *s.parameter;
  if (!(p >= lower && p <= upper)) bad(fmt::format("{} is outside the search's bounds [{}, {}]", p, lower, upper));
  if (!(std::isfinite(s.value) && s.value >= 0))
    bad(fmt::format("the value at the optimum, {}, is no objective value (finite and at least 0)", s.value));
  if (s.at_bound && !lies_on_bound(p, lower, upper))
    bad(fmt::format("{} is not on a bound of [{}, {}], as at_bound says", p, lower, upper));
}

json boundary(const Boundary& b) {
  return {{"name", b.name},
          {"m", b.m},
          {"n", b.n},
          {"bottom", matrix(b.bottom)},
          {"top", matrix(b.top)},
          {"left", matrix(b.left)},
          {"right", matrix(b.right)}};
}
Boundary boundary_of_json(const json& j) {
  Boundary b;
  b.name = j.at("name").get<std::string>();
  b.m = int_of(j.at("m"), "m", 1);
  b.n = int_of(j.at("n"), "n", 1);
  b.bottom = matrix_of(j.at("bottom"));
  b.top = matrix_of(j.at("top"));
  b.left = matrix_of(j.at("left"));
  b.right = matrix_of(j.at("right"));
  // (a record edited to m = 40 over sides of 4 points, or with no bottom, merged with exit 0)
  if (b.bottom.rows() != b.m + 1 || b.top.rows() != b.m + 1 || b.left.rows() != b.n + 1 || b.right.rows() != b.n + 1)
    throw std::invalid_argument(
        fmt::format("the boundary {}: its sides have {}, {}, {} and {} points where m = {} and "
                    "n = {} need {} (bottom, top) and {} (left, right)",
                    b.name, b.bottom.rows(), b.top.rows(), b.left.rows(), b.right.rows(), b.m, b.n, b.m + 1, b.n + 1));
  return b;
}

json sweep_row(const SweepRow& r) {
  const solvers::SolveSummary& s = r.summary;
  const NetMetrics& m = r.metrics;
  return {{"parameter", num(r.parameter)},
          {"mask", {num(r.mask.edge_i), num(r.mask.edge_j), num(r.mask.diag)}},
          {"summary",
           {{"solver", s.solver},
            {"status", to_string(s.status)},
            {"message", s.message},
            {"iterations", s.iterations},
            {"relative_residual", num(s.relative_residual)},
            {"seconds", {num(s.analyze_seconds), num(s.factorize_seconds), num(s.solve_seconds)}},
            {"ordering", s.ordering},
            {"factor_nnz", s.factor_nnz}}},
          {"metrics",
           {num(m.twist_energy), num(m.thin_plate_energy), num(m.dirichlet_energy), num(m.e3_energy),
            num(m.discrete_twist_energy), num(m.discrete_dirichlet_energy), num(m.mask_residual)}},
          {"rms_target", opt(r.rms_target)}};
}
SweepRow sweep_row_of(const json& j) {
  SweepRow r;
  r.parameter = num_of(j.at("parameter"));
  const json& mask = j.at("mask");
  r.mask = {num_of(mask.at(0)), num_of(mask.at(1)), num_of(mask.at(2))};
  const json& s = j.at("summary");
  r.summary.solver = s.at("solver").get<std::string>();
  r.summary.status = enum_of(s.at("status").get<std::string>(), solvers::SolveStatus::kFailure);
  r.summary.message = s.at("message").get<std::string>();
  r.summary.iterations = int_of(s.at("iterations"), "iterations", std::numeric_limits<int>::min());
  r.summary.relative_residual = num_of(s.at("relative_residual"));
  r.summary.analyze_seconds = num_of(s.at("seconds").at(0));
  r.summary.factorize_seconds = num_of(s.at("seconds").at(1));
  r.summary.solve_seconds = num_of(s.at("seconds").at(2));
  r.summary.ordering = s.at("ordering").get<std::string>();
  r.summary.factor_nnz = integer_of(s.at("factor_nnz"), "factor_nnz", std::numeric_limits<std::int64_t>::min(),
                                    std::numeric_limits<std::int64_t>::max());
  const json& m = j.at("metrics");
  NetMetrics& x = r.metrics;
  double* fields[] = {&x.twist_energy,          &x.thin_plate_energy,         &x.dirichlet_energy, &x.e3_energy,
                      &x.discrete_twist_energy, &x.discrete_dirichlet_energy, &x.mask_residual};
  for (size_t k = 0; k < 7; ++k) *fields[k] = num_of(m.at(k));
  r.rms_target = opt_of(j.at("rms_target"));
  return r;
}

json shape(const ShapeEntry& s) {
  json optima = json::array();
  for (const ShapeOptimum& o : s.optima)
    optima.push_back({{"objective", o.objective},
                      {"alpha", summary(o.alpha)},
                      {"mu", summary(o.mu)},
                      {"coons", num(o.coons)},
                      {"laplace", num(o.laplace)},
                      {"weight", o.weight ? summary(*o.weight) : json(nullptr)}});
  json curves = json::array();
  for (const SweepRow& r : s.curves) curves.push_back(sweep_row(r));
  json pictures = json::array();
  for (const auto& [title, net] : s.pictures)
    pictures.push_back({{"title", title}, {"m", net.m}, {"n", net.n}, {"points", matrix(net.points)}});
  return {{"file", s.file},         {"boundary", boundary(s.boundary)},
          {"solver", s.solver},     {"solver_picked_automatically", s.solver_picked_automatically},
          {"optima", optima},       {"weight_solver", s.weight_solver},
          {"one_ring", s.one_ring}, {"curves", curves},
          {"pictures", pictures}};
}
ShapeEntry shape_of(const json& j) {
  ShapeEntry s;
  s.file = j.at("file").get<std::string>();
  s.boundary = boundary_of_json(j.at("boundary"));
  s.solver = j.at("solver").get<std::string>();
  s.solver_picked_automatically = j.at("solver_picked_automatically").get<bool>();
  for (const json& o : j.at("optima")) {
    ShapeOptimum x;
    x.objective = o.at("objective").get<std::string>();
    x.alpha = summary_of(o.at("alpha"));
    x.mu = summary_of(o.at("mu"));
    x.coons = num_of(o.at("coons"));
    x.laplace = num_of(o.at("laplace"));
    if (!o.at("weight").is_null()) x.weight = summary_of(o.at("weight"));
    const std::string what = s.boundary.name + ", " + x.objective;
    const AlphaSearchOptions alpha_bounds;  // the study's α searches use the default bounds
    check_search(x.alpha, alpha_bounds.lower, alpha_bounds.upper, what + ", alpha");
    if (s.boundary.m > 1 && s.boundary.n > 1)
      check_search(x.mu, 0, 1000.0 * s.boundary.m * s.boundary.n, what + ", mu");
    if (x.weight) check_search(*x.weight, 0, 1, what + ", weight");
    s.optima.push_back(std::move(x));
  }
  s.weight_solver = j.at("weight_solver").get<std::string>();
  s.one_ring = j.at("one_ring").get<std::string>();
  for (const json& r : j.at("curves")) s.curves.push_back(sweep_row_of(r));
  for (const json& p : j.at("pictures")) {
    ControlNet net;
    net.m = int_of(p.at("m"), "m", 1);
    net.n = int_of(p.at("n"), "n", 1);
    net.points = matrix_of(p.at("points"));
    if (net.points.rows() != (Eigen::Index(net.m) + 1) * (Eigen::Index(net.n) + 1))
      throw std::invalid_argument("a picture's net has the wrong number of points");
    s.pictures.emplace_back(p.at("title").get<std::string>(), std::move(net));
  }
  return s;
}

json law(const DegreeLawEntry& l) {
  json cells = json::array();
  for (const DegreeCell& c : l.cells)
    cells.push_back({{"degree", c.degree}, {"alpha", summary(c.alpha)}, {"mu", summary(c.mu)}});
  json interior = json::array();
  for (const auto& [d, a] : l.interior) interior.push_back({d, num(a)});
  json fit = nullptr;
  if (l.fit) fit = {{"c", num(l.fit->c)}, {"misfit", num(l.fit->misfit)}};
  return {{"boundary", l.boundary}, {"objective", l.objective}, {"cells", cells}, {"interior", interior}, {"fit", fit}};
}
DegreeLawEntry law_of(const json& j) {
  DegreeLawEntry l;
  l.boundary = j.at("boundary").get<std::string>();
  l.objective = j.at("objective").get<std::string>();
  const AlphaSearchOptions alpha_bounds;
  for (const json& c : j.at("cells")) {
    l.cells.push_back({int_of(c.at("degree"), "degree", 1), summary_of(c.at("alpha")), summary_of(c.at("mu"))});
    const DegreeCell& cell = l.cells.back();
    const std::string what = fmt::format("{}, {}, degree {}", l.boundary, l.objective, cell.degree);
    check_search(cell.alpha, alpha_bounds.lower, alpha_bounds.upper, what + ", alpha");
    check_search(cell.mu, 0, 1000.0 * cell.degree * cell.degree, what + ", mu");
  }
  for (const json& p : j.at("interior"))
    l.interior.emplace_back(int_of(p.at(0), "interior degree", 1), num_of(p.at(1)));
  if (!j.at("fit").is_null()) {
    DegreeLawFit fit;
    fit.c = num_of(j.at("fit").at("c"));
    fit.misfit = num_of(j.at("fit").at("misfit"));
    l.fit = fit;
  }
  return l;
}

json reference(const ReferenceTable& t) {
  json rows = json::array();
  for (const ReferenceRow& r : t.rows)
    rows.push_back({num(r.alpha), num(r.center_z), num(r.thin_plate), num(r.dirichlet), num(r.rms_target)});
  return {{"boundary", t.boundary},       {"m", t.m}, {"n", t.n}, {"rows", rows}, {"best", summary(t.best)},
          {"coons_rms", num(t.coons_rms)}};
}
ReferenceTable reference_of(const json& j) {
  ReferenceTable t;
  t.boundary = j.at("boundary").get<std::string>();
  t.m = int_of(j.at("m"), "m", 1);
  t.n = int_of(j.at("n"), "n", 1);
  for (const json& r : j.at("rows"))
    t.rows.push_back({num_of(r.at(0)), num_of(r.at(1)), num_of(r.at(2)), num_of(r.at(3)), num_of(r.at(4))});
  t.best = summary_of(j.at("best"));
  t.coons_rms = num_of(j.at("coons_rms"));
  return t;
}

json triangle(const TriStudyEntry& e) {
  json rows = json::array();
  for (const TriStudyRow& r : e.rows) {
    json cells = json::array();
    for (const TriStudyCell& c : r.cells)
      cells.push_back({{"degree", c.degree},
                       {"lower", num(c.lower)},
                       {"upper", num(c.upper)},
                       {"c", summary(c.c)},
                       {"quadratic", num(c.quadratic)},
                       {"laplace", num(c.laplace)}});
    rows.push_back({{"objective", r.objective}, {"cells", cells}});
  }
  const tri::TriBoundary& b = e.boundary;
  return {{"file", e.file},
          {"boundary",
           {{"name", b.name}, {"n", b.n}, {"sides", {matrix(b.sides[0]), matrix(b.sides[1]), matrix(b.sides[2])}}}},
          {"solver", e.solver},
          {"solver_picked_automatically", e.solver_picked_automatically},
          {"rows", rows}};
}
TriStudyEntry triangle_of(const json& j) {
  TriStudyEntry e;
  e.file = j.at("file").get<std::string>();
  const json& b = j.at("boundary");
  e.boundary.name = b.at("name").get<std::string>();
  e.boundary.n = int_of(b.at("n"), "n", 1);
  if (!b.at("sides").is_array() || b.at("sides").size() != 3)
    throw std::invalid_argument("the triangle " + e.boundary.name + " has not three sides");
  for (size_t k = 0; k < 3; ++k) {
    e.boundary.sides[k] = matrix_of(b.at("sides").at(k));
    if (e.boundary.sides[k].rows() != e.boundary.n + 1)
      throw std::invalid_argument(fmt::format("the triangle {}: side {} has {} points where n = {} needs {}",
                                              e.boundary.name, k, e.boundary.sides[k].rows(), e.boundary.n,
                                              e.boundary.n + 1));
  }
  e.solver = j.at("solver").get<std::string>();
  e.solver_picked_automatically = j.at("solver_picked_automatically").get<bool>();
  for (const json& r : j.at("rows")) {
    TriStudyRow row;
    row.objective = r.at("objective").get<std::string>();
    for (const json& c : r.at("cells")) {
      row.cells.push_back({int_of(c.at("degree"), "degree", 1), num_of(c.at("lower")), num_of(c.at("upper")),
                           summary_of(c.at("c")), num_of(c.at("quadratic")), num_of(c.at("laplace"))});
      const TriStudyCell& cell = row.cells.back();
      const std::string what = fmt::format("{}, {}, degree {}", e.boundary.name, row.objective, cell.degree);
      const auto [lower, upper] = default_tri_bounds(cell.degree);
      if (cell.lower != lower || cell.upper != upper)
        throw std::invalid_argument(fmt::format("{}: the bounds [{}, {}] are not the study's, [{}, {}]", what,
                                                cell.lower, cell.upper, lower, upper));
      check_search(cell.c, lower, upper, what + ", c");
    }
    e.rows.push_back(std::move(row));
  }
  return e;
}

}  // namespace

json study_part_json(const StudyResult& r) {
  json shapes = json::array(), laws = json::array(), deviations = json::array(), references = json::array(),
       triangles = json::array();
  for (const ShapeEntry& s : r.shapes) shapes.push_back(shape(s));
  for (const DegreeLawEntry& l : r.laws) laws.push_back(law(l));
  for (const FitDeviationEntry& f : r.fit_deviations) {
    json by_degree = json::array();
    for (const auto& [d, dev] : f.max_deviation) by_degree.push_back({d, num(dev)});
    deviations.push_back({{"boundary", f.boundary}, {"max_deviation", by_degree}});
  }
  for (const ReferenceTable& t : r.references) references.push_back(reference(t));
  for (const TriStudyEntry& e : r.triangles) triangles.push_back(triangle(e));
  return {{"shapes", shapes},
          {"laws", laws},
          {"fit_deviations", deviations},
          {"references", references},
          {"triangles", triangles}};
}

void append_study_part(const json& part, const std::string& where, StudyResult* into) {
  try {
    for (const json& s : part.at("shapes")) into->shapes.push_back(shape_of(s));
    for (const json& l : part.at("laws")) into->laws.push_back(law_of(l));
    for (const json& f : part.at("fit_deviations")) {
      FitDeviationEntry e{f.at("boundary").get<std::string>(), {}};
      for (const json& p : f.at("max_deviation"))
        e.max_deviation.emplace_back(int_of(p.at(0), "max_deviation degree", 1), num_of(p.at(1)));
      into->fit_deviations.push_back(std::move(e));
    }
    for (const json& t : part.at("references")) into->references.push_back(reference_of(t));
    for (const json& e : part.at("triangles")) into->triangles.push_back(triangle_of(e));
  } catch (const json::exception& e) {
    throw InputError(where, "result", std::string("malformed: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(where, "result", std::string("malformed: ") + e.what());
  }
}

json bspline_rows_json(const std::vector<BSplineStudyRow>& rows) {
  json out = json::array();
  for (const BSplineStudyRow& r : rows) {
    json notes = json::array();
    for (const CompatibilityNote& n : r.notes) notes.push_back({n.side, n.degree_raised_by, n.knots_inserted});
    json searches = json::array();
    for (const auto& [objective, s] : r.searches) searches.push_back({objective, summary(s)});
    out.push_back({{"file", r.file},
                   {"name", r.name},
                   {"degrees", {r.degree_u, r.degree_v}},
                   {"counts", {r.count_u, r.count_v}},
                   {"notes", notes},
                   {"solver", r.solver},
                   {"thin_plate_coons", num(r.thin_plate_coons)},
                   {"thin_plate_laplace", num(r.thin_plate_laplace)},
                   {"searches", searches}});
  }
  return out;
}

void append_bspline_rows(const json& rows, const std::string& where, std::vector<BSplineStudyRow>* into) {
  try {
    for (const json& j : rows) {
      BSplineStudyRow r;
      r.file = j.at("file").get<std::string>();
      r.name = j.at("name").get<std::string>();
      r.degree_u = int_of(j.at("degrees").at(0), "degrees[0]", 1);
      r.degree_v = int_of(j.at("degrees").at(1), "degrees[1]", 1);
      r.count_u = int_of(j.at("counts").at(0), "counts[0]");
      r.count_v = int_of(j.at("counts").at(1), "counts[1]");
      for (const json& n : j.at("notes"))
        r.notes.push_back(
            {n.at(0).get<std::string>(), int_of(n.at(1), "degree_raised_by"), int_of(n.at(2), "knots_inserted")});
      r.solver = j.at("solver").get<std::string>();
      r.thin_plate_coons = num_of(j.at("thin_plate_coons"));
      r.thin_plate_laplace = num_of(j.at("thin_plate_laplace"));
      for (const json& s : j.at("searches")) r.searches.emplace_back(s.at(0).get<std::string>(), summary_of(s.at(1)));
      // what the study can have written (the key covers the file, not these): the searches within
      // their bounds, energies finite and ≥ 0 (NaN where a solve failed), a net of at least
      // degree + 1 points a side (an α* of 7, a thin plate of -1 and "flat" beside an α merged)
      // (the upper bound is the boundary's own definite end, at most 1/4: bspline_search_options)
      for (const auto& [objective, search] : r.searches) check_search(search, -0.25, 0.25, r.name + ", " + objective);
      for (const auto& [value, what] :
           {std::pair{r.thin_plate_coons, "thin_plate_coons"}, std::pair{r.thin_plate_laplace, "thin_plate_laplace"}})
        if (!std::isnan(value) && !(std::isfinite(value) && value >= 0))
          throw std::invalid_argument(
              fmt::format("{}, {}: {} is no energy (finite and at least 0)", r.name, what, value));
      if (r.count_u < r.degree_u + 1 || r.count_v < r.degree_v + 1)
        throw std::invalid_argument(fmt::format("{}, counts: {} by {} control points cannot carry degrees {} by {}",
                                                r.name, r.count_u, r.count_v, r.degree_u, r.degree_v));
      into->push_back(std::move(r));
    }
  } catch (const json::exception& e) {
    throw InputError(where, "bspline", std::string("malformed: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(where, "bspline", std::string("malformed: ") + e.what());
  }
}

}  // namespace coons
