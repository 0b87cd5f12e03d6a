// The stencil file {"weights": [[...]]} and the free grid: valid input gives the normalised
// stencil, each kind of bad input an InputError naming the field and the index.
#include "coons/io/stencil_json.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "coons/io/input_error.h"

using namespace coons;
using json = nlohmann::json;

namespace {

// The message of the InputError that parsing `text` throws ("" when it does not throw).
std::string error_of(const std::string& text) {
  try {
    (void)stencil_from_json(json::parse(text), "s.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("stencil_from_json: a 5x5 file gives the normalised stencil, centre implied", "[io]") {
  // c1-coons written out: the outer product of (1, −4, 6, −4, 1), centre left out (null).
  const Eigen::Matrix<double, 5, 1> d(1, -4, 6, -4, 1);
  json rows = json::array();
  for (int r = 0; r < 5; ++r) {
    json row = json::array();
    for (int c = 0; c < 5; ++c) row.push_back(r == 2 && c == 2 ? json(nullptr) : json(d(r) * d(c)));
    rows.push_back(row);
  }
  const Stencil s = stencil_from_json(json{{"weights", rows}}, "c1.json");
  CHECK(s.radius == 2);
  CHECK((s.weights - c1_coons_stencil().weights).cwiseAbs().maxCoeff() < 1e-15);
  // the same with the centre written as 0 or as its implied value 36
  rows[2][2] = 0;
  CHECK((stencil_from_json(json{{"weights", rows}}, "c1.json").weights - s.weights).cwiseAbs().maxCoeff() == 0);
  rows[2][2] = 36;
  CHECK((stencil_from_json(json{{"weights", rows}}, "c1.json").weights - s.weights).cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("stencil_from_json: a 3x3 mask-form file gives the alpha stencil", "[io]") {
  // b = α K + β E written as weights with centre implied (−1 = −Σ others): α = −1/4, β = 1/2.
  const Stencil s = stencil_from_json(
      json::parse("{\"weights\": [[-0.25, 0.5, -0.25], [0.5, null, 0.5], [-0.25, 0.5, -0.25]]}"), "f");
  CHECK((s.weights - alpha_stencil(alpha_mask(-0.25)).weights).cwiseAbs().maxCoeff() < 1e-16);
  // point symmetry only (an anisotropic, skewed mask) is accepted
  CHECK(error_of("{\"weights\": [[0.1, 0.2, 0.0], [0.3, null, 0.3], [0.0, 0.2, 0.1]]}").empty());
}

TEST_CASE(
    "stencil_from_json: a pair within 1e-12 of the largest weight is taken as its mean, so the stencil is "
    "symmetric",
    "[io]") {
  // 1e-300 against 0 was accepted and kept as written: a system not quite symmetric for the
  // Cholesky-type backends, which read one triangle
  const Stencil s =
      stencil_from_json(json::parse("{\"weights\": [[1e-300, -1, 0], [-1, null, -1], [0, -1, 0.25e-12]]}"), "s.json");
  CHECK(s.weights(0, 0) == s.weights(2, 2));
  CHECK(s.weights(0, 0) > 0);  // the mean, not either end
  CHECK((s.weights - s.weights.reverse()).cwiseAbs().maxCoeff() == 0);
  // one step beyond the tolerance is refused
  CHECK(error_of("{\"weights\": [[0, -1, 0], [-1, null, -1], [0, -1, 2e-12]]}")
            .rfind("s.json: weights[0][0]: breaks the symmetry", 0) == 0);
}

TEST_CASE("stencil_from_json: bad stencils name the field and the index", "[io]") {
  CHECK(error_of("[1, 2]") == "s.json: a stencil file is a JSON object with \"weights\"");
  CHECK(error_of("{\"w\": 1}") == "s.json: weights: missing");
  CHECK(error_of("{\"weights\": [[1], [2]]}") == "s.json: weights: must be an array of 3 or 5 rows, got 2");
  CHECK(error_of("{\"weights\": [[1, 1, 1], [1, null, 1], [1, 1]]}") ==
        "s.json: weights[2]: must be an array of 3 numbers");
  CHECK(error_of("{\"weights\": [[1, 1, 1], [1, null, \"a\"], [1, 1, 1]]}") ==
        "s.json: weights[1][2]: must be a finite number");
  CHECK(error_of("{\"weights\": [[1, 1, 1], [1, \"c\", 1], [1, 1, 1]]}") ==
        "s.json: weights[1][1]: must be a number or null (the centre is implied)");
  CHECK(error_of("{\"weights\": [[1, 2, 1], [1, null, 1], [1, 1, 1]]}") ==
        "s.json: weights[0][1]: breaks the symmetry W(a, b) = W(-a, -b): 2 here, 1 at weights[2][1]");
  CHECK(error_of("{\"weights\": [[1, -1, 1], [-1, null, -1], [1, -1, 1]]}") ==
        "s.json: weights: the weights around the centre sum to 0, so the implied centre is 0");
  CHECK(
      error_of("{\"weights\": [[1, 1, 1], [1, 5, 1], [1, 1, 1]]}") ==
      "s.json: weights[1][1]: the centre is implied by the others (the weights sum to 0): write null, 0 or -8, not 5");
}

TEST_CASE("free_grid_from_json: a 0/1 grid of the net's shape, errors at the index", "[io]") {
  const FreeGrid g = free_grid_from_json(json::parse("[[0,0,0],[0,1,0],[0,true,0],[0,0,0]]"), 3, 2, "b.json");
  CHECK(g.rows() == 4);
  CHECK(g.cols() == 3);
  CHECK(g.count() == 2);
  CHECK(g(2, 1));
  auto error = [](const std::string& text) {
    try {
      (void)free_grid_from_json(json::parse(text), 2, 1, "b.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error("[[0,0],[0,0]]") == "b.json: free: must be an array of 3 rows (the shape of net), got 2");
  CHECK(error("[[0,0],[0,0,0],[0,0]]") == "b.json: free[1]: must be an array of 2 values 0 or 1");
  CHECK(error("[[0,0],[0,2],[0,0]]") == "b.json: free[1][1]: must be 0 or 1 (an integer, or true/false), not 2");
  CHECK(error("[[0,0],[0,1.0],[0,0]]") == "b.json: free[1][1]: must be 0 or 1 (an integer, or true/false), not 1.0");
}

TEST_CASE("stencil_from_json: weights near the largest double give their stencil without overflow", "[io]") {
  // eight neighbours 1e308: their sum overflows, but the stencil is that of weights 1 (α = β = 1/8)
  const Stencil big = stencil_from_json(
      json::parse("{\"weights\": [[1e308, 1e308, 1e308], [1e308, null, 1e308], [1e308, 1e308, 1e308]]}"), "big.json");
  const Stencil one = stencil_from_json(json::parse("{\"weights\": [[1, 1, 1], [1, null, 1], [1, 1, 1]]}"), "one.json");
  REQUIRE(big.weights.allFinite());
  CHECK((big.weights - one.weights).cwiseAbs().maxCoeff() == 0);
  CHECK(big.weights(0, 0) == -0.125);
  // the centre written out in the same units is accepted, a wrong one named with its implied value
  CHECK(error_of("{\"weights\": [[1e300, 1e300, 1e300], [1e300, -8e300, 1e300], [1e300, 1e300, 1e300]]}").empty());
  const std::string wrong =
      error_of("{\"weights\": [[1e300, 1e300, 1e300], [1e300, 1, 1e300], [1e300, 1e300, 1e300]]}");
  CHECK(wrong.rfind("s.json: weights[1][1]: the centre is implied by the others (the weights sum to 0): write null, "
                    "0 or -8",
                    0) == 0);
  CHECK(wrong.find("e+300, not 1") != std::string::npos);
}
