// Conjugate gradients preconditioned by one V-cycle of Multigrid (multigrid.h): the solver behind
// the `mg-cg` backend. The V-cycle is symmetric (post-smoothing runs the adjoint sweep), so it is
// a valid CG preconditioner on symmetric positive definite stencils.
// Near the rounding floor it restarts from the true residual and returns the best iterate (see
// the comment in the loop). #free unknowns, vectors #free by 1.
// Based on: O. Tatebe, The multigrid preconditioned conjugate gradient method, Sixth Copper
// Mountain Conference on Multigrid Methods, NASA CP 3224 (1993).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "linear_solver.h"
#include "multigrid.h"
#include "multigrid_cycle.h"

namespace coons::solvers {

using namespace mg_detail;

IterationSummary multigrid_cg(const Multigrid& mg, const Vector& b, Vector& x, const IterationOptions& options) {
  IterationSummary out;
  Start start;
  if (!start_solve(mg.levels_, mg.fine_number_, mg.size(), mg.scale_, b, x, out, start)) return out;
  const auto& levels = mg.levels_;
  const Level& L = levels.front();
  const auto& number = mg.fine_number_;
  MultigridOptions cycle_options = mg.options();
  cycle_options.cycle = CycleType::kV;
  const Vector& bg = start.bg;
  Vector& xg = start.xg;
  Vector& r = start.r;
  const double bnorm = start.bnorm;
  double rel = start.rel;
  Vector z, p, q;
  Workspace ws(levels);
  auto precondition = [&](const Vector& res, Vector& zz) {
    zz.setZero(L.points());
    cycle_at(levels, 0, cycle_options, res, zz, CycleType::kV, ws);
  };
  // Near the rounding floor the recursive residual r drifts from b − A x and CG, continued, lets
  // x drift too (at α = −1/4, N = 1023 the true residual grew from 2e−12 to 7e−11 in 40 further
  // iterations). So once r is below the tolerance, or stops decreasing below the estimated floor
  // ε(Σ|w| ‖x‖ + ‖b‖)/‖b‖, the true residual replaces it and CG restarts from there (p = B r);
  // when two restarts in a row gain less than a factor 2, the floor is reached and the best
  // iterate is returned. (The estimate is an upper bound: rounding errors partly cancel, and CG
  // goes on converging below it while r falls, so it alone does not trigger a restart.)
  Vector x_best = xg;
  double best = rel;
  double last_true = rel;  // the lowest true residual at a restart so far
  int restarts_without_gain = 0;
  bool floor_reached = false;
  precondition(r, z);
  p = z;
  double rz = r.dot(z);
  while (rel > options.tolerance && out.iterations < options.max_iterations) {
    if (out.iterations > 0 && options.out_of_time && options.out_of_time()) {
      out.status = SolveStatus::kNotConverged;
      if (rel > best) xg = x_best;
      out.message =
          "time limit reached after " + std::to_string(out.iterations) + " iterations (the best iterate is returned)";
      break;
    }
    if (!(rz > 0)) {
      out.status = SolveStatus::kNotPositiveDefinite;
      out.message = "the V-cycle preconditioner is not positive definite on this operator";
      break;
    }
    apply_level(L, p, q);
    const double pq = p.dot(q);
    if (!(pq > 0)) {
      // Rounding in A p is about ε Σ|w| ‖p‖ per entry: a curvature below that says nothing about
      // definiteness (c1-coons at N = 1023: κ ≈ 1e22 > 1/ε); report the best iterate instead.
      const double noise = std::numeric_limits<double>::epsilon() * abs_weight_sum(L) * p.squaredNorm();
      if (std::isfinite(pq) && std::abs(pq) <= 10 * noise) {
        xg = x_best;
        out.status = SolveStatus::kNotConverged;
        out.message = "conjugate gradients lost the curvature p'Ap to rounding after " +
                      std::to_string(out.iterations) +
                      " iterations (the condition number exceeds what double precision resolves); best iterate "
                      "returned";
        break;
      }
      out.status = SolveStatus::kNotPositiveDefinite;
      out.message = "a curvature p'Ap <= 0: the operator is not positive definite";
      break;
    }
    const double step = rz / pq;
    xg += step * p;
    r -= step * q;
    ++out.iterations;
    const double previous = rel;
    rel = r.norm() / bnorm;
    if (rel <= options.tolerance || (rel >= previous && rel <= rounding_floor(L, xg, bnorm))) {
      residual(L, bg, xg, r);  // the true residual replaces the recursive one
      rel = r.norm() / bnorm;
      out.history.push_back(rel);
      if (rel <= options.tolerance) break;
      const bool gain = rel < 0.5 * last_true;
      last_true = std::min(last_true, rel);
      if (gain) {
        restarts_without_gain = 0;
      } else if (++restarts_without_gain >= 2) {
        if (rel > best) xg = x_best;
        floor_reached = true;
        break;
      }
      if (rel < best) {
        best = rel;
        x_best = xg;
      }
      precondition(r, z);  // restart
      p = z;
      rz = r.dot(z);
      continue;
    }
    out.history.push_back(rel);
    if (rel < best) {  // the recursive residual: the true one agrees until the rounding floor
      best = rel;
      x_best = xg;
    }
    if (stagnated(out.history, 25)) {
      out.status = SolveStatus::kNotConverged;
      out.message = "conjugate gradients stalled at relative residual " + format_g(rel) + " after " +
                    std::to_string(out.iterations) + " iterations";
      break;
    }
    precondition(r, z);
    const double rz_new = r.dot(z);
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  residual(L, bg, xg, r);
  out.relative_residual = r.norm() / bnorm;
  if (!std::isfinite(out.relative_residual)) {
    xg.setZero();
    out.relative_residual = 1;
    out.status = SolveStatus::kDiverged;
    out.message = "conjugate gradients broke down (non-finite values)";
  } else if (out.status == SolveStatus::kSuccess && out.relative_residual > options.tolerance) {
    out.status = SolveStatus::kNotConverged;
    out.message = floor_reached ? floor_message("conjugate gradients", out.relative_residual,
                                                rounding_floor(L, xg, bnorm), out.iterations)
                                : "relative residual " + format_g(out.relative_residual) + " after " +
                                      std::to_string(out.iterations) + " iterations";
  }
  from_grid(number, xg, mg.size(), x);
  return out;
}

}  // namespace coons::solvers
