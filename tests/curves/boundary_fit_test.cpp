#include "coons/curves/boundary_fit.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "coons/io/boundary_curves.h"
#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

TEST_CASE("fit_boundary: polynomial curves are refitted exactly", "[curves]") {
  const std::string path = COONS_DATA_DIR "/boundaries/conoid.json";
  const auto curves = read_boundary_curves(path);
  REQUIRE(curves);
  const Boundary native = read_boundary_file(path).boundary;
  const FittedBoundary f = fit_boundary(*curves, 3, 3, "conoid");
  CHECK(f.max_deviation < 1e-13);
  for (auto [a, b] : {std::pair{&f.boundary.bottom, &native.bottom},
                      {&f.boundary.top, &native.top},
                      {&f.boundary.left, &native.left},
                      {&f.boundary.right, &native.right}})
    CHECK((*a - *b).cwiseAbs().maxCoeff() < 1e-13);
}

TEST_CASE("fit_boundary: the dome's circle arcs converge with the degree, corners bit-identical", "[curves]") {
  const auto curves = read_boundary_curves(COONS_DATA_DIR "/boundaries/dome.json");
  REQUIRE(curves);
  double previous = HUGE_VAL;
  for (int d : {2, 3, 4, 6, 8, 10}) {
    const FittedBoundary f = fit_boundary(*curves, d, d, "dome");
    INFO("degree " << d << ": deviation " << f.max_deviation);
    CHECK(f.max_deviation < previous);
    previous = f.max_deviation;
    const Boundary& b = f.boundary;
    CHECK(b.left.row(0) == b.bottom.row(0));
    CHECK(b.right.row(0) == b.bottom.row(d));
    CHECK(b.left.row(d) == b.top.row(0));
    CHECK(b.right.row(d) == b.top.row(d));
    // every fitted control point of the bottom side lies in its plane y = −1
    CHECK((b.bottom.col(1).array() + 1).abs().maxCoeff() < 1e-12);
  }
  CHECK(previous < 1e-10);
}

TEST_CASE("fit_boundary: at degree 1000 the control polygon stays on the dome's arcs", "[curves]") {
  // Fitted by least squares at degree 1000 directly, the inner control points of these arcs
  // (radius √2, every point within 2 of the origin) reached 140.
  const auto curves = read_boundary_curves(COONS_DATA_DIR "/boundaries/dome.json");
  REQUIRE(curves);
  const FittedBoundary f = fit_boundary(*curves, 1000, 1000, "dome");
  CHECK(f.max_deviation < 1e-12);
  for (const Eigen::MatrixX3d* side : {&f.boundary.bottom, &f.boundary.top, &f.boundary.left, &f.boundary.right}) {
    CHECK(side->rows() == 1001);
    CHECK(side->rowwise().norm().maxCoeff() < 2.1);
    // a polygon converging to the arc: its second differences are O(1/n²)
    const Eigen::Index k = side->rows() - 2;
    const Eigen::MatrixX3d d2 = side->topRows(k) - 2 * side->middleRows(1, k) + side->bottomRows(k);
    CHECK(d2.rowwise().norm().maxCoeff() < 10.0 / (1000.0 * 1000.0));
  }
}

TEST_CASE("read_boundary_curves: a file without curves has none, bad curves name the field", "[curves]") {
  CHECK(!read_boundary_curves(COONS_DATA_DIR "/boundaries/pillow.json"));
  const std::string bad = (std::filesystem::temp_directory_path() / "coons_bad_curves.json").string();
  std::ofstream(bad) << R"({"curves": {"bottom": {"expr": ["t", "sin(", "0"]}, "top": {"expr": ["t","1","0"]},
                          "left": {"expr": ["0","t","0"]}, "right": {"expr": ["1","t","0"]}}})";
  CHECK_THROWS_WITH(read_boundary_curves(bad), Catch::Contains("curves.bottom"));
  std::filesystem::remove(bad);
}
