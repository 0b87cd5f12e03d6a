// Triangular nets made in code with fixed seeds (tests of coons::tri). The namespace is tri_test,
// not tri::test: in the unity build of scripts/sanitize.sh a file's `using namespace coons::tri`
// reaches the files after it, where `test::` would then name two namespaces.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include "coons/tri/tri_net.h"
#include "solvers/registry.h"

namespace coons::tri_test {

//! Uniformly random points in [−1, 1]³.
inline tri::TriNet random_tri_net(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dist(-1, 1);
  tri::TriNet net(n);
  for (Eigen::Index r = 0; r < net.points.rows(); ++r)
    for (int c = 0; c < 3; ++c) net.points(r, c) = dist(rng);
  return net;
}

//! A random quadratic (degree 2) patch elevated to degree n ≥ 2.
inline tri::TriNet elevated_quadratic(int n, std::uint32_t seed) {
  return tri::elevate_degree(random_tri_net(2, seed), n - 2);
}

//! A random random-affine patch (degree 1) elevated to degree n ≥ 1.
inline tri::TriNet elevated_linear(int n, std::uint32_t seed) {
  return tri::elevate_degree(random_tri_net(1, seed), n - 1);
}

//! The sparse LU backend (the triangular systems are nonsymmetric).
inline const solvers::SolverInfo& lu() { return *solvers::find_solver("eigen-lu"); }

//! n! as a double (exact up to 22!).
inline double factorial(int n) { return std::tgamma(n + 1.0); }

//! max |a − b| over all coordinates.
inline double max_abs_difference(const tri::TriNet& a, const tri::TriNet& b) {
  return (a.points - b.points).cwiseAbs().maxCoeff();
}

//! The six permutations of (i, j, k) in the convention of permuted().
inline const std::array<std::array<int, 3>, 6>& all_permutations() {
  static const std::array<std::array<int, 3>, 6> p = {
      {{0, 1, 2}, {1, 0, 2}, {0, 2, 1}, {2, 1, 0}, {1, 2, 0}, {2, 0, 1}}};
  return p;
}

}  // namespace coons::tri_test
