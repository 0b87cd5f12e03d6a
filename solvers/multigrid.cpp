#include "multigrid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "multigrid_levels.h"

namespace coons::solvers {

bool MultigridOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (pre_smoothing < 0 || post_smoothing < 0) return fail("smoothing sweeps must be >= 0");
  if (pre_smoothing + post_smoothing < 1) return fail("a cycle needs at least one smoothing sweep");
  if (coarsest_unknowns < 1) return fail("coarsest_unknowns must be >= 1");
  if (max_levels < 1) return fail("max_levels must be >= 1");
  return true;
}

Multigrid::Multigrid() = default;
Multigrid::~Multigrid() = default;
Multigrid::Multigrid(Multigrid&&) noexcept = default;
Multigrid& Multigrid::operator=(Multigrid&&) noexcept = default;

namespace {

using namespace mg_detail;

constexpr Eigen::Index kMinThreadedPoints = 2048;

// Vectors of every level for one solve (allocated once, not per cycle): the rhs and correction of
// the coarse problems, a residual and the smoother's scratch.
struct Workspace {
  std::vector<Vector> rhs, x, residual, work;
  explicit Workspace(const std::vector<Level>& levels)
      : rhs(levels.size()), x(levels.size()), residual(levels.size()), work(levels.size()) {}
};

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

}  // namespace

SolveStatus Multigrid::setup(const StencilOperator& op, const MultigridOptions& options, std::string* message) {
  levels_.clear();
  fine_number_.clear();
  options_ = options;
  std::string why;
  if (!op.is_valid(&why) || !options.is_valid(&why)) {
    if (message) *message = why;
    return SolveStatus::kFailure;
  }
  if (op.size() == 0) {
    if (message) *message = "the grid has no free points";
    return SolveStatus::kFailure;
  }
  Level fine;
  fine.rows = op.rows;
  fine.cols = op.cols;
  fine.radius = op.radius;
  fine.constant = true;
  fine.coef = op.weights;
  fine.free = op.free.empty() ? std::vector<unsigned char>(std::size_t(op.rows) * op.cols, 1) : op.free;
  for (auto& f : fine.free) f = f ? 1 : 0;
  fine.unknowns = std::count(fine.free.begin(), fine.free.end(), 1);
  fine_number_ = free_numbering(op);
  levels_.push_back(std::move(fine));
  while (true) {
    const Level& L = levels_.back();
    if (L.unknowns <= options.coarsest_unknowns || std::min(L.rows, L.cols) < 3 ||
        int(levels_.size()) >= options.max_levels)
      break;
    const bool cubic = options.interpolation == Interpolation::kCubic ||
                       (options.interpolation == Interpolation::kAuto && op.radius == 2);
    Level coarse = galerkin_coarse(L, cubic ? 3 : 1);
    if (coarse.unknowns == 0) break;
    levels_.push_back(std::move(coarse));
  }
  // Coarse levels run on one thread: below a few thousand points a parallel region costs more than
  // it saves (the results are the same for every count).
  for (auto& L : levels_) L.threads = L.points() >= kMinThreadedPoints ? resolved_threads(options.threads) : 1;
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l)
    if (!factor_lines(levels_[l])) {
      if (message) *message = "a line block of level " + std::to_string(l) + " has a zero pivot";
      levels_.clear();
      return SolveStatus::kSingular;
    }
  if (!setup_direct(levels_.back())) {
    if (message)
      *message = "the coarsest system (" + std::to_string(levels_.back().unknowns) + " unknowns) is singular";
    levels_.clear();
    return SolveStatus::kSingular;
  }
  return SolveStatus::kSuccess;
}

bool Multigrid::ready() const { return !levels_.empty(); }

Eigen::Index Multigrid::size() const { return levels_.empty() ? 0 : levels_.front().unknowns; }

std::vector<MultigridLevelInfo> Multigrid::levels() const {
  std::vector<MultigridLevelInfo> out;
  for (const Level& L : levels_) out.push_back({L.rows, L.cols, L.radius, L.unknowns});
  return out;
}

namespace {

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
struct Start {
  Vector bg, xg, r;
  double bnorm = 0, rel = 0;
};

bool start_solve(const std::vector<Level>& levels, const std::vector<Eigen::Index>& number, Eigen::Index size,
                 const Vector& b, Vector& x, IterationSummary& out, Start& s) {
  if (levels.empty() || b.size() != size) {
    out.status = SolveStatus::kFailure;
    out.message = levels.empty() ? "setup() has not succeeded" : "right-hand side of the wrong size";
    return false;
  }
  if (x.size() != b.size()) x.setZero(b.size());
  to_grid(number, b, s.bg);
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

}  // namespace

void Multigrid::apply(const Vector& x, Vector& y) const {
  if (!ready()) {
    y.setZero(x.size());
    return;
  }
  Vector g, h;
  to_grid(fine_number_, x, g);
  apply_level(levels_.front(), g, h);
  from_grid(fine_number_, h, size(), y);
}

void Multigrid::precondition(const Vector& r, Vector& z) const {
  if (!ready()) {  // no hierarchy: the identity
    z = r;
    return;
  }
  Vector g, h = Vector::Zero(levels_.front().points());
  to_grid(fine_number_, r, g);
  Workspace ws(levels_);
  cycle_at(levels_, 0, options_, g, h, options_.cycle, ws);
  from_grid(fine_number_, h, size(), z);
}

IterationSummary Multigrid::solve(const Vector& b, Vector& x, const IterationOptions& options) const {
  IterationSummary out;
  Start start;
  if (!start_solve(levels_, fine_number_, size(), b, x, out, start)) return out;
  const Level& L = levels_.front();
  const Vector& bg = start.bg;
  Vector& xg = start.xg;
  Vector& r = start.r;
  const double bnorm = start.bnorm;
  double rel = start.rel;
  Workspace ws(levels_);
  // The best iterate is kept: when rounding makes the cycle amplify (c1-coons at N = 1023, where
  // κ ≈ 1e22 > 1/ε, the residual fell to 5e−7 and then grew tenfold per cycle), it is returned.
  Vector x_best = xg;
  double best = rel;
  while (rel > options.tolerance && out.iterations < options.max_iterations) {
    cycle_at(levels_, 0, options_, bg, xg, options_.cycle, ws);
    ++out.iterations;
    residual(L, bg, xg, r);
    rel = r.norm() / bnorm;
    out.history.push_back(rel);
    if (!std::isfinite(rel) || rel > options.divergence * out.history.front() || rel > 1e3 * best) {
      out.status = SolveStatus::kDiverged;
      out.message = "the multigrid iteration diverged: residual grew from " + format_g(best) + " to " + format_g(rel) +
                    " (the best iterate is returned)";
      xg = x_best;
      residual(L, bg, xg, r);
      rel = r.norm() / bnorm;
      break;
    }
    if (rel < best) {
      best = rel;
      x_best = xg;
    }
    if (rel > options.tolerance && stagnated(out.history, 10)) {
      out.status = SolveStatus::kNotConverged;
      if (rel > best) {
        xg = x_best;
        rel = best;
      }
      const double floor = rounding_floor(L, xg, bnorm);
      out.message = rel <= 100 * floor ? floor_message("the multigrid iteration", rel, floor, out.iterations)
                                       : "the multigrid iteration stalled at relative residual " + format_g(rel) +
                                             " after " + std::to_string(out.iterations) + " cycles";
      break;
    }
    if (rel > options.tolerance && options.out_of_time && options.out_of_time()) {
      out.status = SolveStatus::kNotConverged;
      if (rel > best) {
        xg = x_best;
        rel = best;
      }
      out.message = "time limit reached at relative residual " + format_g(rel) + " after " +
                    std::to_string(out.iterations) + " cycles (the best iterate is returned)";
      break;
    }
  }
  out.relative_residual = rel;
  if (out.status == SolveStatus::kSuccess && rel > options.tolerance) {
    out.status = SolveStatus::kNotConverged;
    out.message = "relative residual " + format_g(rel) + " after " + std::to_string(out.iterations) + " cycles";
  }
  from_grid(fine_number_, xg, size(), x);
  return out;
}

IterationSummary multigrid_cg(const Multigrid& mg, const Vector& b, Vector& x, const IterationOptions& options) {
  IterationSummary out;
  Start start;
  if (!start_solve(mg.levels_, mg.fine_number_, mg.size(), b, x, out, start)) return out;
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
