// The degree law of the optimal mask: α*(n) + 1/4 ≈ c/n², fitted by least squares over the degrees
// with an interior optimum (minimise Σ (a_d + 1/4 − c/d²)², so c = Σ (a_d + 1/4)/d² / Σ 1/d⁴),
// with the largest relative misfit max |(a_d + 1/4) − c/d²| / |a_d + 1/4|.
// Based on: docs/math.md §4 (α(n) = −n²/(4(n² + μ)), so α + 1/4 = μ/(4n²) + O(n⁻⁴)).
#pragma once

#include <optional>
#include <utility>
#include <vector>

namespace coons {

struct DegreeLawFit {
  double c = 0;       //!< α* + 1/4 ≈ c/n²
  double misfit = 0;  //!< largest relative deviation of a point from the law
};

//! (degree, α*) pairs; nullopt with fewer than two points.
std::optional<DegreeLawFit> fit_degree_law(const std::vector<std::pair<int, double>>& optima);

}  // namespace coons
