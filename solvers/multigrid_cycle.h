// The pieces of a multigrid iteration that Multigrid::solve (multigrid.cpp) and multigrid_cg
// (multigrid_cg.cpp) share: the recursive cycle with its per-solve workspace, the map between the
// free-point numbering and grid vectors, the common start of a solve and the rounding floor of
// the fine operator. Internal to the solvers layer.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "iteration_summary.h"
#include "multigrid.h"
#include "multigrid_levels.h"

namespace coons::solvers::mg_detail {

//! Vectors of every level for one solve (allocated once, not per cycle): the rhs and correction of
//! the coarse problems, a residual and the smoother's scratch.
struct Workspace {
  std::vector<Vector> rhs, x, residual, work;
  explicit Workspace(const std::vector<Level>& levels)
      : rhs(levels.size()), x(levels.size()), residual(levels.size()), work(levels.size()) {}
};

//! One cycle of `type` from level l down: x ← x + (one cycle's correction) for A_l x = b.
void cycle_at(const std::vector<Level>& levels, std::size_t l, const MultigridOptions& o, const Vector& b, Vector& x,
              CycleType type, Workspace& ws);

//! g (grid, zero at fixed points) from v (free points, numbered by `number`), and back.
void to_grid(const std::vector<Eigen::Index>& number, const Vector& v, Vector& g);
void from_grid(const std::vector<Eigen::Index>& number, const Vector& g, Eigen::Index n, Vector& v);

//! Σ|w| of the fine level's (constant) stencil.
double abs_weight_sum(const Level& L);
//! ε (Σ|w| ‖x‖ + ‖b‖) / ‖b‖: the relative residual rounding alone leaves in b − A x.
double rounding_floor(const Level& L, const Vector& x, double bnorm);
//! "WHAT stopped at the rounding floor: …" for a solve that ends there.
std::string floor_message(const char* what, double rel, double floor, int iterations);

//! The common start of a solve: grid vectors of b and x, ‖b‖ and the first relative residual.
struct Start {
  Vector bg, xg, r;
  double bnorm = 0, rel = 0;
};
//! bg is b / scale (the levels hold A / scale). False when the solve ends here (out is then final:
//! a failure, or b = 0 with x = 0).
bool start_solve(const std::vector<Level>& levels, const std::vector<Eigen::Index>& number, Eigen::Index size,
                 double scale, const Vector& b, Vector& x, IterationSummary& out, Start& s);

}  // namespace coons::solvers::mg_detail
