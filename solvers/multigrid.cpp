#include "multigrid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "multigrid_cycle.h"
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

using namespace mg_detail;

namespace {

constexpr Eigen::Index kMinThreadedPoints = 2048;

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
  scale_ = 1;
  if (const auto form = integer_separable_form(op)) {
    const int width = op.width();
    for (int a = 0; a < width; ++a)
      for (int b = 0; b < width; ++b)
        fine.coef[std::size_t(a) * std::size_t(width) + std::size_t(b)] =
            form->along_i[std::size_t(a)] * form->along_j[std::size_t(b)];
    fine.factor_i = form->along_i;
    fine.factor_j = form->along_j;
    scale_ = form->scale;
  }
  fine.free = op.free.empty() ? std::vector<unsigned char>(std::size_t(op.rows) * op.cols, 1) : op.free;
  for (auto& f : fine.free) f = f ? 1 : 0;
  fine.unknowns = std::count(fine.free.begin(), fine.free.end(), 1);
  fine_number_ = free_numbering(op);
  levels_.push_back(std::move(fine));
  while (true) {
    Level& L = levels_.back();
    find_common_stencil(L);  // (galerkin_coarse copies the coarse stencil over L's common region)
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
      if (message)
        *message = "a line block of level " + std::to_string(l) +
                   " has a zero pivot: the line smoother's elimination without pivoting cannot handle this stencil";
      levels_.clear();
      return SolveStatus::kNotApplicable;
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

void Multigrid::apply(const Vector& x, Vector& y) const {
  if (!ready()) {
    y.setZero(x.size());
    return;
  }
  Vector g, h;
  to_grid(fine_number_, x, g);
  apply_level(levels_.front(), g, h);
  from_grid(fine_number_, h, size(), y);
  if (scale_ != 1) y *= scale_;
}

void Multigrid::precondition(const Vector& r, Vector& z) const {
  if (!ready()) {  // no hierarchy: the identity
    z = r;
    return;
  }
  Vector g, h = Vector::Zero(levels_.front().points());
  to_grid(fine_number_, r, g);
  if (scale_ != 1) g /= scale_;
  Workspace ws(levels_);
  cycle_at(levels_, 0, options_, g, h, options_.cycle, ws);
  from_grid(fine_number_, h, size(), z);
}

IterationSummary Multigrid::solve(const Vector& b, Vector& x, const IterationOptions& options) const {
  IterationSummary out;
  Start start;
  if (!start_solve(levels_, fine_number_, size(), scale_, b, x, out, start)) return out;
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
      // (the best may be the start, x = 0, with residual 1: the report's residual is the best's)
      out.message = "the multigrid iteration diverged: residual grew from " + format_g(best) + " to " + format_g(rel) +
                    " (the best iterate, relative residual " + format_g(best) + ", is returned)";
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

}  // namespace coons::solvers
