#include "multigrid_cycle.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace coons::solvers::mg_detail {

void cycle_at(const std::vector<Level>& levels, std::size_t l, const MultigridOptions& o, const Vector& b, Vector& x,
              CycleType type, Workspace& ws) {
  const Level& L = levels[l];
  if (l + 1 == levels.size()) {
    solve_direct(L, b, x);
    return;
  }
  for (int s = 0; s < o.pre_smoothing; ++s) smooth(L, b, x, ws.work[l], true);
  Vector& r = ws.residual[l];
  Vector& bc = ws.rhs[l + 1];
  Vector& xc = ws.x[l + 1];
  residual(L, b, x, r);
  restrict_to(L, levels[l + 1], r, bc);
  xc.setZero(levels[l + 1].points());
  cycle_at(levels, l + 1, o, bc, xc, type, ws);
  if (type == CycleType::kF) cycle_at(levels, l + 1, o, bc, xc, CycleType::kV, ws);
  prolong_add(L, levels[l + 1], xc, x);
  for (int s = 0; s < o.post_smoothing; ++s) smooth(L, b, x, ws.work[l], false);
}

void to_grid(const std::vector<Eigen::Index>& number, const Vector& v, Vector& g) {
  g.setZero(Eigen::Index(number.size()));
  for (std::size_t p = 0; p < number.size(); ++p)
    if (number[p] >= 0) g[Eigen::Index(p)] = v[number[p]];
}

void from_grid(const std::vector<Eigen::Index>& number, const Vector& g, Eigen::Index n, Vector& v) {
  v.resize(n);
  for (std::size_t p = 0; p < number.size(); ++p)
    if (number[p] >= 0) v[number[p]] = g[Eigen::Index(p)];
}

// The relative residual that rounding alone leaves in b − A x: ε (Σ|w| ‖x‖ + ‖b‖) / ‖b‖, an upper
// bound of ε ‖|A||x| + |b|‖ / ‖b‖ (each shifted copy of x has norm ≤ ‖x‖). With κ(A) ≈ 1.8e11
// (α = −1/4, N = 1023) and data whose right-hand side is small (second differences of a smooth
// boundary), it reaches 1e−12.
double abs_weight_sum(const Level& L) {  // of the fine level, which has one stencil
  double sum = 0;
  for (int k = 0; k < L.width() * L.width(); ++k) sum += std::abs(L.coef[std::size_t(k)]);
  return sum;
}

double rounding_floor(const Level& L, const Vector& x, double bnorm) {
  return std::numeric_limits<double>::epsilon() * (abs_weight_sum(L) * x.norm() + bnorm) / bnorm;
}

std::string floor_message(const char* what, double rel, double floor, int iterations) {
  char text[320];
  std::snprintf(text, sizeof text,
                "%s stopped at the rounding floor: relative residual %.3g after %d iterations (double precision "
                "attains about %.2g here: eps*(sum|w|*|x| + |b|)/|b|); the tolerance is below it",
                what, rel, iterations, floor);
  return text;
}

// The common start of Multigrid::solve and multigrid_cg: the checks, the grid vectors of b and x,
// ‖b‖ and the first residual (in out.history). False when the solve ends here, out then final:
// a failure, or b = 0 with the solution x = 0.

bool start_solve(const std::vector<Level>& levels, const std::vector<Eigen::Index>& number, Eigen::Index size,
                 double scale, const Vector& b, Vector& x, IterationSummary& out, Start& s) {
  if (levels.empty() || b.size() != size) {
    out.status = SolveStatus::kFailure;
    out.message = levels.empty() ? "setup() has not succeeded" : "right-hand side of the wrong size";
    return false;
  }
  if (x.size() != b.size()) x.setZero(b.size());
  to_grid(number, b, s.bg);
  if (scale != 1) s.bg /= scale;
  to_grid(number, x, s.xg);
  s.bnorm = s.bg.norm();
  if (s.bnorm == 0) {
    x.setZero(b.size());
    out.history = {0};
    return false;
  }
  residual(levels.front(), s.bg, s.xg, s.r);
  s.rel = s.r.norm() / s.bnorm;
  out.history.push_back(s.rel);
  return true;
}

}  // namespace coons::solvers::mg_detail
