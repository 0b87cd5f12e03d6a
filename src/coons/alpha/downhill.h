// Internal to the one-parameter searches (search_run.h, coons/study/tri_search.cpp): from a scan
// point downhill to a point where the slope vanishes, inside the bracket of its neighbours, with
// singular members (poles of the objective) possibly inside it. Where f′(g) < 0 and f(end) ≥ f(g),
// or f grows without bound at a singular parameter before `end`, a minimum below f(g) lies
// between g and end. The bracket [lo, hi] keeps f′ pointing downhill at lo with f(lo) ≤ f(g), and
// at hi f′ pointing back or f ≥ f(lo); each step is a secant on f′ where the ends' slopes differ
// in sign, else a bisection (at least every other step). Mirrored where f′(g) > 0.
// Sizes: two evaluations kept, besides those the caller's evaluator makes.
// Based on: R. P. Brent, Algorithms for Minimization without Derivatives, Prentice-Hall (1973),
// ch. 4 (a bracket kept by bisection while secant steps converge: Dekker's safeguard).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace coons::detail {

template <class Evaluation>
struct Downhill {
  Evaluation lowest;                 //!< the lowest point with a downhill (or stopping) slope
  std::optional<Evaluation> failed;  //!< the evaluation that failed, where one did (the walk stops there)
};

//! From g (slope not zero) towards `end` (the neighbour on its downhill side): evaluate(c) gives an
//! Evaluation with parameter, value, derivative and ok(). Stops once stop(lowest) holds, the
//! bracket is at most `tolerance` wide or after max_steps evaluations, or at a failed one.
template <class Evaluation, class Evaluate, class Stop>
Downhill<Evaluation> go_downhill(Evaluate&& evaluate, Evaluation g, double end, double tolerance, int max_steps,
                                 Stop&& stop) {
  const double direction = g.derivative < 0 ? 1 : -1;
  Downhill<Evaluation> out{std::move(g), std::nullopt};
  Evaluation& lo = out.lowest;
  std::optional<Evaluation> hi;  // with its slope, once evaluated
  double hi_at = end;
  bool bisect = false;
  for (int it = 0; it < max_steps && !stop(lo) && std::abs(hi_at - lo.parameter) > tolerance; ++it) {
    double c = 0.5 * (lo.parameter + hi_at);
    if (!bisect && hi && hi->derivative * lo.derivative < 0) {
      const double secant = hi_at - hi->derivative * (hi_at - lo.parameter) / (hi->derivative - lo.derivative);
      if (secant > std::min(lo.parameter, hi_at) && secant < std::max(lo.parameter, hi_at)) c = secant;
    }
    const double width = std::abs(hi_at - lo.parameter);
    Evaluation e = evaluate(c);
    if (!e.ok()) {
      out.failed = std::move(e);
      return out;
    }
    if (e.value <= lo.value && (e.derivative * direction < 0 || stop(e))) {
      lo = std::move(e);
    } else {
      hi_at = c;
      hi = std::move(e);
    }
    bisect = !bisect && std::abs(hi_at - lo.parameter) > width / 2;
  }
  return out;
}

}  // namespace coons::detail
