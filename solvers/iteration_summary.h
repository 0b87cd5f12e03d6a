// What an iterative method of this layer reports on one right-hand side: the status (the same
// enum as every backend), the iterations, the relative residual ‖b − A x‖/‖b‖ reached and its
// history (index 0 is the start), and the mean convergence factor per iteration.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "linear_solver.h"

namespace coons::solvers {

//! When an iteration stops: at ‖b − A x‖/‖b‖ ≤ tolerance, or after max_iterations.
struct IterationOptions {
  double tolerance = 1e-10;
  int max_iterations = 200;
  //! A residual this many times the starting one means the iteration diverges.
  double divergence = 1e8;
  //! When set, asked after every iteration: true stops it (a time limit) with not_converged, the
  //! best iterate and a message saying so. LinearSolver passes its SolverOptions::time_limit_seconds.
  std::function<bool()> out_of_time;

  bool is_valid(std::string* why) const {
    auto fail = [&](const char* reason) {
      if (why) *why = reason;
      return false;
    };
    if (!(tolerance > 0 && tolerance < 1)) return fail("tolerance must lie in (0, 1)");
    if (max_iterations < 1) return fail("max_iterations must be >= 1");
    if (!(divergence > 1)) return fail("divergence must be > 1");
    return true;
  }
};

struct IterationSummary {
  SolveStatus status = SolveStatus::kSuccess;
  std::string message;  //!< empty on success, otherwise why
  int iterations = 0;
  double relative_residual = 0;  //!< ‖b − A x‖ / ‖b‖ at the end (‖b‖ = 0: 0, x = 0)
  std::vector<double> history;   //!< relative residual after 0, 1, 2, ... iterations

  //! (history.back() / history.front())^(1/iterations): the mean reduction per iteration.
  [[nodiscard]] double convergence_factor() const {
    if (iterations <= 0 || history.size() < 2 || !(history.front() > 0)) return 0;
    return std::pow(history.back() / history.front(), 1.0 / double(history.size() - 1));
  }
  [[nodiscard]] bool ok() const { return status == SolveStatus::kSuccess; }
};

//! A relative residual at most this is near the rounding floor of the systems coons meets (1e-16 on
//! small nets, 3e-12 at degree 40): only there does a residual that stops falling mean stagnation.
//! Above it a residual may stay flat for thousands of iterations and fall again (SOR with ω = 1.99
//! on a degree-20 net: flat at 0.028 for over 1000 sweeps, then steadily down to 1e-12).
inline constexpr double kStagnationFloor = 1e-9;

//! How IterationEnd::stagnation words a residual that set no new low for `iterations` iterations.
inline std::string no_new_low(int iterations) {
  return "no smaller residual in the last " + std::to_string(iterations) + " iterations";
}

//! True when the last `window` entries of a residual history improved on the best before them by
//! less than 10 %: the iteration has stalled (e.g. at the rounding floor of an ill-conditioned
//! system) and further iterations are wasted.
inline bool stagnated(const std::vector<double>& history, std::size_t window) {
  if (history.size() < 2 * window + 1) return false;
  const auto split = history.end() - std::ptrdiff_t(window);
  const double before = *std::min_element(history.begin(), split);
  const double recent = *std::min_element(split, history.end());
  return recent > 0.9 * before;
}

}  // namespace coons::solvers
