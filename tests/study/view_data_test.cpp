// The data of the `coons view` page (coons/study/view_data.h): the α family's nets, energies and optima.
#include "coons/study/view_data.h"

#include <catch2/catch.hpp>

#include "coons/metrics/energies.h"
#include "coons/net/coons_net.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;

TEST_CASE("alpha_view_slider: the frames hold the family's nets, their energies and the optima", "[study][view]") {
  const Boundary b = test::make_smooth_boundary(5, 4, 7);
  ViewOptions options;
  options.frames = 11;
  options.samples = 5;
  options.objectives = {"thin_plate", "dirichlet"};
  const solvers::SolverInfo* solver = solvers::find_solver("eigen-ldlt");
  REQUIRE(solver);
  const ViewSlider s = alpha_view_slider(b, options, *solver, -0.2);
  std::string why;
  ViewPage page;
  page.sliders.push_back(s);
  REQUIRE(page.is_valid(&why));
  CHECK(s.parameter == "alpha");
  CHECK(s.net_edges.size() == size_t(6 * 4 + 5 * 5));
  CHECK(s.faces.size() == size_t(2 * 4 * 4));
  REQUIRE(s.curves.size() == 2);
  REQUIRE(s.frames.size() >= 11);
  for (const ViewFrame& f : s.frames) {
    CHECK(f.ok);
    CHECK(f.net.rows() == 30);
    CHECK(f.points.rows() == 25);
  }
  // the frame at α = −1/4 is the discrete Coons net
  const ViewFrame& coons = s.frames.front();
  CHECK(coons.parameter == -0.25);
  CHECK((coons.net - discrete_coons_net(b).points).cwiseAbs().maxCoeff() < 1e-9);
  // the curves are the exact energies of the frames' nets
  for (size_t k = 0; k < s.frames.size(); k += 3) {
    ControlNet net(5, 4);
    net.points = s.frames[k].net;
    CHECK(s.curves[0].values[k] == Approx(thin_plate_energy(net)).epsilon(1e-12));
    CHECK(s.curves[1].values[k] == Approx(dirichlet_energy(net)).epsilon(1e-12));
  }
  // each optimum is a frame, and no frame of its curve is lower
  for (const ViewCurve& c : s.curves) {
    if (!c.optimum) continue;
    size_t at = s.frames.size();
    for (size_t k = 0; k < s.frames.size(); ++k)
      if (s.frames[k].parameter == *c.optimum) at = k;
    REQUIRE(at < s.frames.size());
    for (double v : c.values) CHECK(v >= c.values[at] * (1 - 1e-9));
  }
  // the surface samples lie on the net's Bézier surface: the corners are the net's corners
  CHECK((s.frames[3].points.row(0) - s.frames[3].net.row(0)).norm() < 1e-12);
  CHECK((s.frames[3].points.row(24) - s.frames[3].net.row(29)).norm() < 1e-12);
}

TEST_CASE("ViewOptions::is_valid: frames, samples, the interval and the curves", "[study][view]") {
  std::string why;
  CHECK(ViewOptions{}.is_valid(&why));
  ViewOptions o;
  o.frames = 1;
  CHECK_FALSE(o.is_valid(&why));
  o = ViewOptions{};
  o.upper = 0.3;
  CHECK_FALSE(o.is_valid(&why));
  o = ViewOptions{};
  o.objectives = {"target"};
  CHECK_FALSE(o.is_valid(&why));
  CHECK(why.find("target") != std::string::npos);
}
