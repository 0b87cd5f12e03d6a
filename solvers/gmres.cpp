#include "gmres.h"

#include <Eigen/IterativeLinearSolvers>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace coons::solvers {
namespace {
// A new Arnoldi direction shorter than this fraction of A z is taken as rounding (a breakdown).
constexpr double kBreakdown = 16 * std::numeric_limits<double>::epsilon();
}  // namespace

bool GmresOptions::is_valid(std::string* why) const {
  if (restart < 1) {
    if (why) *why = "restart must be >= 1";
    return false;
  }
  return iteration.is_valid(why);
}

IterationSummary gmres(const VectorMap& apply, const VectorMap& precondition, const Eigen::VectorXd& b,
                       Eigen::VectorXd& x, const GmresOptions& options) {
  using Vector = Eigen::VectorXd;
  IterationSummary out;
  const Eigen::Index n = b.size();
  if (x.size() != n) x.setZero(n);
  if (std::string why; !options.is_valid(&why)) {  // x = 0, and the residual of that x
    x.setZero(n);
    out.status = SolveStatus::kFailure;
    out.message = "invalid options: " + why;
    out.relative_residual = b.isZero(0) ? 0 : 1;
    return out;
  }
  const double bnorm = b.norm();
  if (bnorm == 0) {
    x.setZero(n);
    out.history = {0};
    return out;
  }
  const int k = options.restart;
  const double tol = options.iteration.tolerance;
  Vector r, w, z, Ax;
  apply(x, Ax);
  r = b - Ax;
  double rel = r.norm() / bnorm;
  if (!std::isfinite(rel)) {  // squares that overflow: no Arnoldi step would be finite either
    out.status = SolveStatus::kFailure;
    out.message = "GMRES cannot start: the norm of the right-hand side or of the first residual overflows";
    out.relative_residual = 1;
    out.history = {1};
    x.setZero(n);
    return out;
  }
  out.history.push_back(rel);
  std::vector<Vector> V(static_cast<std::size_t>(k) + 1), Z(static_cast<std::size_t>(k));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(k + 1, k);
  Vector cs(k), sn(k), g(k + 1);
  const auto& out_of_time = options.iteration.out_of_time;
  bool timed_out = false;
  while (rel > tol && out.iterations < options.iteration.max_iterations) {
    const double beta = r.norm();
    V[0] = r / beta;
    g.setZero();
    g[0] = beta;
    int j = 0;
    for (; j < k && out.iterations < options.iteration.max_iterations; ++j) {
      if (out.iterations > 0 && out_of_time && out_of_time()) {
        timed_out = true;
        break;
      }
      if (precondition)
        precondition(V[std::size_t(j)], Z[std::size_t(j)]);
      else
        Z[std::size_t(j)] = V[std::size_t(j)];
      apply(Z[std::size_t(j)], w);
      const double before = w.norm();
      for (int i = 0; i <= j; ++i) {  // modified Gram–Schmidt
        H(i, j) = w.dot(V[std::size_t(i)]);
        w -= H(i, j) * V[std::size_t(i)];
      }
      const double next = w.norm();
      H(j + 1, j) = next;
      for (int i = 0; i < j; ++i) {  // earlier rotations on the new column
        const double t = cs[i] * H(i, j) + sn[i] * H(i + 1, j);
        H(i + 1, j) = -sn[i] * H(i, j) + cs[i] * H(i + 1, j);
        H(i, j) = t;
      }
      const double d = std::hypot(H(j, j), H(j + 1, j));
      cs[j] = d > 0 ? H(j, j) / d : 1;
      sn[j] = d > 0 ? H(j + 1, j) / d : 0;
      H(j, j) = d;
      H(j + 1, j) = 0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      ++out.iterations;
      const double estimate = std::abs(g[j + 1]) / bnorm;
      out.history.push_back(estimate);
      // Stop the cycle when converged, at a breakdown or at non-finite values (the cycle's solution
      // is then rejected below). A breakdown: what is left of A z after the orthogonalisation is
      // rounding of A z itself (next = 0 in exact arithmetic: the solution is in the space). Taken
      // as a direction, that rounding would make the least-squares problem ill-posed: on the 2 × 2
      // [[1, 1], [1, 1 + 1e-10]], b = (1, −1), with ILUT, ten such steps led to a residual of 1e25.
      if (!(estimate > tol) || !(next > kBreakdown * before) || !std::isfinite(next)) {
        ++j;
        break;
      }
      V[std::size_t(j) + 1] = w / next;
    }
    if (j == 0) {
      if (timed_out) {
        out.status = SolveStatus::kNotConverged;
        out.message = "time limit reached at relative residual " + format_g(rel) + " after " +
                      std::to_string(out.iterations) + " iterations";
      }
      break;
    }
    // x += Z y with H(0:j, 0:j) y = g(0:j)
    Vector y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    if (!y.allFinite()) {
      out.status = SolveStatus::kFailure;
      out.message = "GMRES broke down: the Hessenberg system is singular";
      break;
    }
    for (int i = 0; i < j; ++i) x += y[i] * Z[std::size_t(i)];
    apply(x, Ax);
    r = b - Ax;
    const double true_rel = r.norm() / bnorm;
    if (!std::isfinite(true_rel) || true_rel > options.iteration.divergence * out.history.front()) {
      out.status = SolveStatus::kDiverged;
      out.message = "GMRES diverged (residual " + format_g(true_rel) + ")";
      x.setZero(n);
      r = b;
      rel = 1;
      break;
    }
    if (timed_out && !(true_rel <= tol)) {
      rel = true_rel;
      out.status = SolveStatus::kNotConverged;
      out.message = "time limit reached at relative residual " + format_g(rel) + " after " +
                    std::to_string(out.iterations) + " iterations";
      break;
    }
    if (true_rel >= rel && !(true_rel <= tol)) {  // a whole cycle without progress: stagnation
      rel = true_rel;
      out.status = SolveStatus::kNotConverged;
      out.message = "GMRES stagnated at relative residual " + format_g(rel);
      break;
    }
    rel = true_rel;
  }
  out.relative_residual = rel;
  if (out.status == SolveStatus::kSuccess && rel > tol) {
    out.status = SolveStatus::kNotConverged;
    out.message = "relative residual " + format_g(rel) + " after " + std::to_string(out.iterations) + " iterations";
  }
  return out;
}

VectorMap ilut_preconditioner(const Eigen::SparseMatrix<double>& A, std::string* message, double drop_tolerance,
                              int fill_factor) {
  auto ilu = std::make_shared<Eigen::IncompleteLUT<double>>();
  ilu->setDroptol(drop_tolerance);
  ilu->setFillfactor(fill_factor);
  ilu->compute(A);
  if (ilu->info() != Eigen::Success) {
    if (message) *message = "the incomplete LU factorisation failed";
    return {};
  }
  return [ilu](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = ilu->solve(in); };
}

}  // namespace coons::solvers
