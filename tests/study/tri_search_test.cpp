#include "coons/study/tri_search.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/config.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/tri/tri_energy.h"
#include "tri/tri_fixtures.h"

using namespace coons;
using namespace coons::tri;
using namespace coons::tri_test;

namespace {

TriObjective objective(const std::string& text) {
  std::string why;
  const auto o = parse_tri_objective(text, &why);
  INFO(why);
  REQUIRE(o);
  return *o;
}

}  // namespace

TEST_CASE("parse_tri_objective: names and weighted sums, unknown names are refused", "[study][tri]") {
  const TriObjective o = objective("thin_plate+0.5*twist+2*discrete_dirichlet");
  REQUIRE(o.terms.size() == 3);
  REQUIRE(o.terms[1] == std::make_pair(TriTerm::kTwist, 0.5));
  REQUIRE(o.terms[2] == std::make_pair(TriTerm::kDiscreteDirichlet, 2.0));
  REQUIRE_FALSE(o.uses_target());
  REQUIRE(objective("target").uses_target());
  std::string why;
  REQUIRE(objective("e3+2*thin_plate").terms[0] == std::make_pair(TriTerm::kE3, 1.0));
  for (const char* bad : {"e4", "thin_plate+", "-1*twist", "x*twist", ""}) {
    INFO(bad);
    REQUIRE_FALSE(parse_tri_objective(bad, &why));
    REQUIRE_FALSE(why.empty());
  }
}

TEST_CASE("evaluate_tri_objective: the derivative from one extra solve equals a central difference", "[study][tri]") {
  Target sphere;
  sphere.kind = Target::Kind::kSphere;
  sphere.radius = 1.5;
  sphere.samples = 9;
  for (const int n : {3, 5, 8}) {
    const TriNet frame = frame_net(boundary_of(random_tri_net(n, 40 + n)));
    for (const char* name : {"thin_plate", "dirichlet", "twist", "e3", "discrete_thin_plate", "discrete_dirichlet",
                             "discrete_twist", "target", "thin_plate+3*target"}) {
      TriObjective o = objective(name);
      o.target = sphere;
      for (const double c : {-0.15, 0.0, 0.2}) {
        const TriEvaluation e = evaluate_tri_objective(frame, o, c, lu(), true);
        REQUIRE(e.ok());
        const double h = 1e-5;
        const double plus = evaluate_tri_objective(frame, o, c + h, lu(), false).value;
        const double minus = evaluate_tri_objective(frame, o, c - h, lu(), false).value;
        const double difference = (plus - minus) / (2 * h);
        INFO(name << ", n = " << n << ", c = " << c << ": " << e.derivative << " vs " << difference);
        REQUIRE(e.derivative == Approx(difference).epsilon(1e-6).margin(1e-8 * (1 + std::abs(e.value))));
      }
    }
  }
}

TEST_CASE("evaluate_tri_objective: the derivative does not depend on where the boundary lies", "[study][tri]") {
  TriNet net = random_tri_net(7, 90);
  const TriNet frame = frame_net(boundary_of(net));
  net.points.rowwise() += Eigen::RowVector3d(3e5, -2e5, 1e5);
  const TriNet moved = frame_net(boundary_of(net));
  for (const char* name : {"thin_plate", "dirichlet", "twist", "discrete_twist"}) {
    const TriEvaluation here = evaluate_tri_objective(frame, objective(name), -0.1, lu(), true);
    const TriEvaluation there = evaluate_tri_objective(moved, objective(name), -0.1, lu(), true);
    INFO(name << ": " << here.derivative << " vs " << there.derivative);
    REQUIRE(there.derivative == Approx(here.derivative).epsilon(1e-6).margin(1e-9 * here.value));
  }
}

TEST_CASE("search_tri_c: a boundary far from the origin has the optimum and values it has at the origin",
          "[study][tri]") {
  // A random boundary with x on the grid of the doubles near 2^47 (steps of 1/32), moved there
  // exactly: it was solved where it lay, its energies were rounding noise, and the search called
  // it flat (monkey_saddle at 2^47; at 2^43 c* was -0.04636 for -0.04762), also because the
  // rounding floor of its flatness test measured the frame's zeros inside.
  TriNet net = random_tri_net(6, 77);
  net.points.col(0) = (net.points.col(0) * 32).array().round() / 32;
  const TriNet frame = frame_net(boundary_of(net));
  TriNet far = frame;
  far.points.col(0).array() += std::ldexp(1.0, 47);
  REQUIRE((far.points.col(0).array() - std::ldexp(1.0, 47)).matrix() == frame.points.col(0));
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(6);
  for (const char* name : {"thin_plate", "e3"}) {
    const AlphaSearchSummary here = search_tri_c(frame, objective(name), lu(), options);
    const AlphaSearchSummary there = search_tri_c(far, objective(name), lu(), options);
    INFO(name << ": " << there.brief_report());
    REQUIRE(here.status == SearchStatus::kSuccess);
    CHECK(there.status == SearchStatus::kSuccess);
    REQUIRE(there.parameter.has_value());
    CHECK(*there.parameter == Approx(*here.parameter).margin(1e-9));
    CHECK(there.value == Approx(here.value).epsilon(1e-9));
  }
  // monkey_saddle with x on the grid of the doubles near 2^47 (steps of 1/32) and moved there: it
  // was flat, also once solved about its centre, because the flatness test's rounding floor
  // measured the frame's zeros inside, 2^47 away. (At 1e15 its extent, 1.6, is within 16 eps of
  // its position: one point, and flat, as the rectangle's search has it.)
  tri::TriBoundary saddle = read_tri_boundary_file(COONS_DATA_DIR "/triangles/monkey_saddle.json");
  for (Eigen::MatrixX3d& side : saddle.sides) side.col(0) = (side.col(0) * 32).array().round() / 32;
  const TriNet saddle_here = frame_net(saddle);
  TriNet saddle_there = saddle_here;
  saddle_there.points.col(0).array() += std::ldexp(1.0, 47);
  REQUIRE((boundary_of(saddle_there).sides[0].col(0).array() - std::ldexp(1.0, 47)).matrix() == saddle.sides[0].col(0));
  const AlphaSearchSummary here = search_tri_c(saddle_here, objective("thin_plate"), lu(), options);
  const AlphaSearchSummary there = search_tri_c(saddle_there, objective("thin_plate"), lu(), options);
  INFO(there.brief_report());
  REQUIRE(here.status == SearchStatus::kSuccess);
  CHECK(there.status == SearchStatus::kSuccess);
  REQUIRE(there.parameter.has_value());
  CHECK(*there.parameter == Approx(*here.parameter).margin(1e-9));
  // the solve too: the interior is the one at the origin moved, to the rounding of its coordinates
  const TriSolveResult at_origin = solve_tri_net(frame), moved = solve_tri_net(far);
  REQUIRE(moved.summary.ok());
  Eigen::MatrixX3d back = moved.net.points;
  back.col(0).array() -= std::ldexp(1.0, 47);
  CHECK((back - at_origin.net.points).cwiseAbs().maxCoeff() <= 1.0 / 64);  // half a step of x there
  for (int side = 0; side < 3; ++side)                                     // the data bit for bit
    CHECK(boundary_of(moved.net).sides[side] == boundary_of(far).sides[side]);
}

TEST_CASE("search_tri_c: a boundary that is one point to within rounding is flat", "[study][tri]") {
  // (1, 2, 3) at degree 6 with z a few ulps off at four points, the spread of an elevated constant
  // side: once the flatness floor was measured on the boundary alone, the search reported an
  // optimum of noise (c = -0.118, value 2.8e-30)
  TriNet net(6);
  net.points.rowwise() = Eigen::RowVector3d(1, 2, 3);
  const double off = std::nextafter(3.0, 4.0);
  for (const auto& [j, k] : {std::pair{1, 0}, std::pair{6, 0}, std::pair{0, 2}, std::pair{0, 5}})
    net.at(6 - j - k, j, k)(2) = off;
  const TriNet frame = frame_net(boundary_of(net));
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(6);
  for (const char* name : {"thin_plate", "e3", "dirichlet"}) {
    const AlphaSearchSummary s = search_tri_c(frame, objective(name), lu(), options);
    INFO(name << ": " << s.brief_report());
    CHECK(s.status == SearchStatus::kFlat);
    CHECK_FALSE(s.parameter.has_value());
  }
}

TEST_CASE("search_tri_c: the optimum is the minimum of a fine scan, inside the bounds", "[study][tri]") {
  for (const std::uint32_t seed : {1u, 2u, 3u, 4u}) {
    const int n = 5 + int(seed % 3);
    const TriNet frame = frame_net(boundary_of(random_tri_net(n, 500 + seed)));
    const TriObjective o = objective(seed == 4 ? "e3" : "thin_plate");
    AlphaSearchOptions options;
    std::tie(options.lower, options.upper) = default_tri_bounds(n);
    const AlphaSearchSummary s = search_tri_c(frame, o, lu(), options);
    REQUIRE(s.status == SearchStatus::kSuccess);
    REQUIRE(s.parameter);
    double best = HUGE_VAL, best_c = 0;
    for (int k = 0; k <= 400; ++k) {
      const double c = options.lower + (options.upper - options.lower) * k / 400;
      const double v = evaluate_tri_objective(frame, o, c, lu(), false).value;
      if (v < best) best = v, best_c = c;
    }
    INFO("seed " << seed << ": search " << *s.parameter << " (" << s.value << "), scan " << best_c << " (" << best
                 << ")");
    REQUIRE(s.value <= best * (1 + 1e-12));
    REQUIRE(std::abs(*s.parameter - best_c) <= (options.upper - options.lower) / 400);
    if (!s.at_bound)
      REQUIRE(std::abs(evaluate_tri_objective(frame, o, *s.parameter, lu(), true).derivative) < 1e-6 * s.value);
  }
}

TEST_CASE("search_tri_c: an affine boundary is flat, no optimum is claimed", "[study][tri]") {
  const TriNet frame = frame_net(boundary_of(elevated_linear(7, 3)));
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(7);
  for (const char* name : {"thin_plate", "dirichlet", "twist", "e3"}) {
    const AlphaSearchSummary s = search_tri_c(frame, objective(name), lu(), options);
    REQUIRE(s.status == SearchStatus::kFlat);
    REQUIRE(s.flat);
    REQUIRE_FALSE(s.parameter);
  }
}

TEST_CASE("search_tri_c: e3 of a quadratic patch's boundary is least, 0, at c = -1/6", "[study][tri]") {
  // c = −1/6 alone reproduces the quadratic (docs/math.md §9), whose third derivatives vanish
  for (const int n : {4, 7}) {
    const TriNet frame = frame_net(boundary_of(elevated_quadratic(n, 60 + n)));
    AlphaSearchOptions options;
    std::tie(options.lower, options.upper) = default_tri_bounds(n);
    const AlphaSearchSummary s = search_tri_c(frame, objective("e3"), lu(), options);
    INFO("n = " << n << ": c* = " << (s.parameter ? *s.parameter : NAN) << ", E3 " << s.value);
    REQUIRE(s.status == SearchStatus::kSuccess);
    REQUIRE(s.parameter);
    REQUIRE(std::abs(*s.parameter + 1.0 / 6) < 1e-6);
    REQUIRE(evaluate_tri_objective(frame, objective("e3"), 0.0, lu(), false).value > 1e-3);
  }
}

TEST_CASE("default_tri_bounds: between the singular member c*_n and 1/3, around -1/6", "[study][tri]") {
  for (int n = 3; n <= 40; ++n) {
    const auto [lower, upper] = default_tri_bounds(n);
    REQUIRE(lower < -1.0 / 6);
    REQUIRE(upper == Approx(1.0 / 3));
    if (n >= 4) REQUIRE(lower > -1.0 / 6 - 1.0 / (2.0 * (n - 3)));
  }
}

TEST_CASE("search_tri_c: a Cholesky-type backend fails the search instead of giving a wrong optimum", "[study][tri]") {
  const TriNet frame = frame_net(boundary_of(random_tri_net(6, 77)));
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(6);
  const AlphaSearchSummary s =
      search_tri_c(frame, objective("thin_plate"), *solvers::find_solver("eigen-ldlt"), options);
  REQUIRE((s.status == SearchStatus::kFailedRegion || s.status == SearchStatus::kSolverFailed));
  REQUIRE_FALSE(s.parameter);
  REQUIRE(s.failed_evaluations > 0);
}

TEST_CASE("search_tri_c: consecutive failed evaluations are reported as one failed interval", "[study][tri]") {
  // a Cholesky-type backend takes only c = 0 (the symmetric member): the scan points below and above
  // it fail, two runs of two points each
  const TriNet frame = frame_net(boundary_of(random_tri_net(6, 77)));
  AlphaSearchOptions options;
  options.lower = -0.5;
  options.upper = 0.5;
  options.scan_points = 5;
  const AlphaSearchSummary s =
      search_tri_c(frame, objective("thin_plate"), *solvers::find_solver("eigen-ldlt"), options);
  CHECK(s.status == SearchStatus::kFailedRegion);
  CHECK(s.failed_evaluations == 4);
  const std::vector<std::pair<double, double>> runs = {{-0.5, -0.25}, {0.25, 0.5}};
  CHECK(s.failed_intervals == runs);
}

namespace {

// The search with bounds [lower, upper] and the given number of scan points.
AlphaSearchSummary search_between(const TriNet& frame, const char* name, double lower, double upper, int scan = 9) {
  AlphaSearchOptions options;
  options.lower = lower;
  options.upper = upper;
  options.scan_points = scan;
  return search_tri_c(frame, objective(name), lu(), options);
}

// The planar right triangle of degree 5 with straight, evenly spaced sides, two of its side
// points lifted by `bump` and -bump/2 out of the plane.
TriNet bumped_triangle(double bump) {
  TriNet net(5);
  for (int i = 0; i <= 5; ++i)
    for (int j = 0; i + j <= 5; ++j) net.at(i, j, 5 - i - j) = Eigen::RowVector3d(i / 5.0, j / 5.0, 0);
  net.at(2, 0, 3)(2) = bump;
  net.at(4, 1, 0)(2) = -bump / 2;
  return frame_net(boundary_of(net));
}

// The octant of the unit sphere: each side the same degree-6 fit of a quarter circle (as in
// data/triangles/sphere_octant.json), turned (x, y, z) -> (y, z, x) from side to side.
TriNet sphere_octant() {
  const double a[] = {
      1.0, 0.9999947147044073, 0.9177791934631556, 0.7531915534523025, 0.5235675415000569, 0.26180541585248346, 0.0};
  TriBoundary boundary;
  boundary.n = 6;
  for (auto& side : boundary.sides) side.resize(7, 3);
  for (int k = 0; k <= 6; ++k) {
    const double x = a[k], y = a[6 - k];  // the quarter circle is symmetric about x = y
    boundary.sides[0].row(k) << x, y, 0;
    boundary.sides[1].row(k) << 0, x, y;
    boundary.sides[2].row(k) << y, 0, x;
  }
  return frame_net(boundary);
}

// The degree-n triangle whose side points are f(u, v, w) = (u, v, sin(3u)·v + 2w² + 3uv) at the
// barycentric points (i, j, k)/n of its sides.
TriNet sine_bump_triangle(int n) {
  const auto f = [n](int i, int j, int k) {
    const double u = double(i) / n, v = double(j) / n, w = double(k) / n;
    return Eigen::RowVector3d(u, v, std::sin(3 * u) * v + 2 * w * w + 3 * u * v);
  };
  TriBoundary boundary;
  boundary.n = n;
  for (auto& side : boundary.sides) side.resize(n + 1, 3);
  for (int t = 0; t <= n; ++t) {
    boundary.sides[0].row(t) = f(n - t, t, 0);
    boundary.sides[1].row(t) = f(0, n - t, t);
    boundary.sides[2].row(t) = f(t, 0, n - t);
  }
  return frame_net(boundary);
}

}  // namespace

TEST_CASE("search_tri_c: every minimum of the scan is refined and the lowest result kept", "[study][tri]") {
  // Over [-1, 1.5] the scan of the degree-8 bump has two minima: 1.1875 (the lowest point) and
  // -0.0625, with c*_8 = -4/15 and c = 1, singular, around them. The lowest point alone led to
  // c = 1.1737 (Dirichlet 3.4935) as success; the narrow basin of -0.0625 holds the minimum the
  // bounds [-0.3, 0.3] find, c = -0.24444 (3.29925), which an exact rational solve confirms.
  const TriNet frame = sine_bump_triangle(8);
  const AlphaSearchSummary narrow = search_between(frame, "dirichlet", -0.3, 0.3);
  REQUIRE(narrow.status == SearchStatus::kSuccess);
  CHECK(*narrow.parameter == Approx(-0.24444104808).margin(1e-9));
  const AlphaSearchSummary wide = search_between(frame, "dirichlet", -1, 1.5);
  INFO(to_string(wide.status) << ": " << wide.message);
  REQUIRE(wide.status == SearchStatus::kSuccess);
  CHECK(wide.local_minima == 2);
  CHECK(*wide.parameter == Approx(*narrow.parameter).margin(1e-9));
  CHECK(wide.value == Approx(narrow.value).epsilon(1e-12));
  CHECK(wide.value < 3.3);  // the other basin bottoms out at 3.4935
  CHECK_THAT(wide.message, Catch::Contains("the scan saw 2 minima; each was refined and the lowest result kept"));
}

TEST_CASE("search_tri_c: bounds that hold singular members give the minimum the default bounds give", "[study][tri]") {
  // Over [-5, 5] the bracket of the lowest scan point held c*_6 = -1/3 and 2/3, where the energy
  // grows without bound; golden section on the values crossed them and reported a point 0.03 from
  // the minimum as success, and over [-100, 100] the scan point c = 0 itself.
  for (const std::uint32_t seed : {0u, 11u, 12u}) {
    const TriNet frame = seed == 0 ? sphere_octant() : frame_net(boundary_of(random_tri_net(6, seed)));
    const auto [lower, upper] = default_tri_bounds(6);
    const AlphaSearchSummary reference = search_between(frame, "thin_plate", lower, upper);
    REQUIRE(reference.status == SearchStatus::kSuccess);
    REQUIRE_FALSE(reference.at_bound);
    for (const double wide : {5.0, 100.0}) {
      const AlphaSearchSummary s = search_between(frame, "thin_plate", -wide, wide);
      INFO("seed " << seed << ", bounds +-" << wide << ": " << to_string(s.status) << " " << s.message);
      REQUIRE(s.status == SearchStatus::kSuccess);
      CHECK(*s.parameter == Approx(*reference.parameter).margin(1e-7));
      CHECK(s.value == Approx(reference.value).epsilon(1e-12));
    }
  }
}

TEST_CASE("search_tri_c: a nearly planar triangle is not flat, its optimum that of larger bumps", "[study][tri]") {
  // Against the energy of the frame filled with its centroid (of the size of the boundary), bumps of
  // 3e-7 read as flat, though the objective varies by a factor of 4.6 over the bounds.
  const auto [lower, upper] = default_tri_bounds(5);
  const AlphaSearchSummary large = search_between(bumped_triangle(1), "thin_plate", lower, upper);
  REQUIRE(large.status == SearchStatus::kSuccess);
  for (const double bump : {3e-7, 1e-9}) {
    const AlphaSearchSummary s = search_between(bumped_triangle(bump), "thin_plate", lower, upper);
    INFO("bump " << bump << ": " << to_string(s.status) << " " << s.message);
    REQUIRE(s.status == SearchStatus::kSuccess);
    CHECK_FALSE(s.flat);
    CHECK(*s.parameter == Approx(*large.parameter).margin(1e-6));
  }
  // and the plane itself is flat
  CHECK(search_between(bumped_triangle(0), "thin_plate", lower, upper).status == SearchStatus::kFlat);
}

TEST_CASE("search_tri_c: a singular scan point away from the optimum is skipped and named", "[study][tri]") {
  // The scan of [-0.5, 0] in 7 points meets c*_6 = -1/3; the lowest point and its neighbours lie
  // above it. Every failed scan point made the search failed_region, exit 3.
  const TriNet frame = frame_net(boundary_of(random_tri_net(6, 11)));
  const AlphaSearchSummary s = search_between(frame, "thin_plate", -0.5, 0, 7);
  INFO(to_string(s.status) << " " << s.message);
  REQUIRE(s.failed_evaluations == 1);
  REQUIRE(s.failed_intervals.size() == 1);
  CHECK(s.failed_intervals[0].first == Approx(-1.0 / 3));
  REQUIRE(s.parameter);
  REQUIRE(*s.parameter > -0.25);  // the optimum's bracket is clear of the failure
  CHECK(s.status == SearchStatus::kSuccess);
  CHECK(s.message.find("away from the optimum") != std::string::npos);
}
