#include "fast5_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "separable_banded_solver.h"
#include "sine_transform.h"

namespace coons::solvers {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr std::array<double, 5> kDelta4 = {1, -4, 6, -4, 1};
constexpr std::array<double, 5> kDelta2 = {0, 1, -2, 1, 0};
constexpr std::array<double, 5> kImpulse = {0, 0, 1, 0, 0};
constexpr double kCapacitanceTolerance = 1e-14;
constexpr int kRefinements = 2;             // at most this many refinement steps per right-hand side
constexpr double kRefinedResidual = 1e-11;  // relative residual at which refinement stops

double c_weight(int di, int dj) { return kDelta4[std::size_t(di) + 2] * kDelta4[std::size_t(dj) + 2]; }
double t_weight(int di, int dj) {
  const auto i = std::size_t(di) + 2, j = std::size_t(dj) + 2;
  return kDelta4[i] * kImpulse[j] + 2 * kDelta2[i] * kDelta2[j] + kImpulse[i] * kDelta4[j];
}

// sqrt(2/(n+1))·sin(kπ/(n+1)), k = 1..n: the orthonormal DST-I of e_1.
Eigen::VectorXd first_sine_column(int n) {
  Eigen::VectorXd s(n);
  for (int k = 0; k < n; ++k) s[k] = std::sqrt(2.0 / (n + 1)) * std::sin(M_PI * (k + 1) / (n + 1));
  return s;
}

// 2 − 2cos(kπ/(n+1)), k = 1..n: the eigenvalues of tridiag(−1, 2, −1).
Eigen::VectorXd second_difference_eigenvalues(int n) {
  Eigen::VectorXd e(n);
  for (int k = 0; k < n; ++k) e[k] = 4 * std::pow(std::sin(M_PI * (k + 1) / (2.0 * (n + 1))), 2);
  return e;
}

// One parity block of the capacitance matrix in the sine basis along i:
//   Cap·v = diag ⊙ v − kappa·u (uᵀv) − G (Gᵀv),   symmetric positive definite.
struct CapacitanceBlock {
  std::vector<int> modes;  // modes p (0-based) along i of this block
  Eigen::VectorXd diag, u;
  double kappa = 0;
  Eigen::MatrixXd G;  // #modes by #(modes q of the column parity)

  void apply(const Eigen::MatrixXd& V, Eigen::MatrixXd& out) const {
    out.noalias() = diag.asDiagonal() * V;
    out.noalias() -= (kappa * u) * (u.transpose() * V);
    out.noalias() -= G * (G.transpose() * V);  // one read of G for every right-hand side
  }

  // Conjugate gradients with the diagonal as preconditioner, one column per right-hand side
  // (each with its own step lengths; a converged column is frozen); returns the iterations.
  int solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& X) const {
    const Eigen::Index n = rhs.rows(), m = rhs.cols();
    X.setZero(n, m);
    if (n == 0 || m == 0) return 0;
    Eigen::ArrayXd target = kCapacitanceTolerance * rhs.colwise().norm().transpose().array();
    Eigen::MatrixXd R = rhs, Z = diag.cwiseInverse().asDiagonal() * R, P = Z, AP;
    Eigen::ArrayXd rz = (R.cwiseProduct(Z)).colwise().sum().transpose().array();
    std::vector<bool> active(static_cast<std::size_t>(m), false);
    for (Eigen::Index c = 0; c < m; ++c) active[std::size_t(c)] = target[c] > 0;
    const int limit = int(2 * n + 50);
    for (int k = 1; k <= limit; ++k) {
      apply(P, AP);
      bool any = false;
      for (Eigen::Index c = 0; c < m; ++c) {
        if (!active[std::size_t(c)]) continue;
        const double step = rz[c] / P.col(c).dot(AP.col(c));
        X.col(c) += step * P.col(c);
        R.col(c) -= step * AP.col(c);
        if (R.col(c).norm() <= target[c]) {
          active[std::size_t(c)] = false;
          P.col(c).setZero();
          continue;
        }
        Z.col(c) = R.col(c).cwiseQuotient(diag);
        const double rz_next = R.col(c).dot(Z.col(c));
        P.col(c) = Z.col(c) + (rz_next / rz[c]) * P.col(c);
        rz[c] = rz_next;
        any = true;
      }
      if (!any) return k;
    }
    return limit;
  }
};

// The unknown-independent checks of fast5: a grid operator, every point free, a·C + b·T.
bool describe(const LinearOperator& op, SolveSummary& summary, C1FamilyWeights* weights) {
  if (!op.grid) {
    summary.message = "needs the 5x5 grid operator (a full rectangle with an a*C + b*T stencil)";
    return false;
  }
  const StencilOperator& g = *op.grid;
  if (std::string why = grid_operator_problem(g, op.matrix); !why.empty()) {
    summary.message = why;
    return false;
  }
  if (g.size() != Eigen::Index(g.rows) * g.cols) {
    summary.message = "needs a full rectangle (every grid point free); use pcg-fast for other free sets";
    return false;
  }
  const auto w = c1_family_weights(g);
  if (!w) {
    summary.message = "the stencil is not a*C + b*T with a, b >= 0 (c1-coons, c1-family, biharmonic)";
    return false;
  }
  if (weights) *weights = *w;
  return true;
}

class Fast5Solver final : public LinearSolver {
 public:
  explicit Fast5Solver(const SolverOptions& options) : LinearSolver(options) {}
  [[nodiscard]] std::string name() const override { return "fast5"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (!describe(op, summary, nullptr)) return SolveStatus::kNotApplicable;
    R_ = op.grid->rows;
    C_ = op.grid->cols;
    const unsigned planning = detail::fft_planning(options_);
    along_i_ = detail::SineTransform(R_, planning);
    along_j_ = detail::SineTransform(C_, planning);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    C1FamilyWeights w;
    if (!describe(op, summary, &w)) return SolveStatus::kNotApplicable;
    weights_ = w;
    separable_ = !(w.b > 1e-12 * w.a);
    if (separable_) return SolveStatus::kSuccess;
    factor_modes();
    build_capacitance();
    summary.factor_nnz = 3LL * R_ * C_;
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    if (separable_) {  // a·P⊗P
      SeparableBandedOperator sep;
      sep.rows = R_;
      sep.cols = C_;
      sep.along_i = {6 * weights_.a, -4 * weights_.a, weights_.a};
      sep.along_j = {6, -4, 1};
      summary.iterations = 1;
      const SolveStatus status = separable_banded_solve(sep, B, X);
      if (status != SolveStatus::kSuccess) summary.message = "a zero pivot in the banded LDL^T of a factor";
      return status;
    }
    X.resize(B.rows(), 3);
    std::array<const double*, 3> rhs{};
    std::array<double*, 3> out{};
    for (int c = 0; c < 3; ++c) {
      rhs[std::size_t(c)] = B.col(c).data();
      out[std::size_t(c)] = X.col(c).data();
    }
    int iterations = solve_columns(rhs, out, 3);
    // The capacitance operator is formed from differences of large terms (the sine-basis
    // inverses of the modes next to the corner cancel), so the first solve loses digits that
    // grow with N; iterative refinement on the true residual (O(rows·cols)) restores them,
    // for the columns whose residual is still above kRefinedResidual, all of them in one pass.
    for (int k = 0; k < kRefinements; ++k) {
      int count = 0;
      for (int c = 0; c < 3; ++c) {
        const Eigen::Map<const RowMajor> b(B.col(c).data(), R_, C_);
        Eigen::Map<RowMajor> x(X.col(c).data(), R_, C_);
        RowMajor& r = residuals_[std::size_t(count)];
        apply_operator(x, r);
        r = b - r;
        if (!(r.norm() > kRefinedResidual * b.norm())) continue;
        corrections_[std::size_t(count)].resize(R_, C_);
        rhs[std::size_t(count)] = r.data();
        out[std::size_t(count)] = corrections_[std::size_t(count)].data();
        targets_[std::size_t(count)] = c;
        ++count;
      }
      if (count == 0) break;
      iterations = std::max(iterations, solve_columns(rhs, out, count));
      for (int c = 0; c < count; ++c) {
        Eigen::Map<RowMajor> x(X.col(targets_[std::size_t(c)]).data(), R_, C_);
        x += corrections_[std::size_t(c)];
      }
    }
    summary.iterations = iterations;
    return SolveStatus::kSuccess;
  }

 private:
  // The banded LDLᵀ of M_q = (aν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I for every mode q along j,
  // stored row-major by (row r, mode q) so that the passes along i run across the modes.
  void factor_modes() {
    const double a = weights_.a, b = weights_.b;
    nu_ = second_difference_eigenvalues(C_);
    inv_d_.setZero(R_, C_);
    l1_.setZero(R_, C_);
    l2_.setZero(R_, C_);
    BandedLdlt f;
    for (int q = 0; q < C_; ++q) {
      const double alpha = a * nu_[q] * nu_[q] + b, beta = 2 * b * nu_[q], gamma = b * nu_[q] * nu_[q];
      banded_ldlt({6 * alpha + 2 * beta + gamma, -4 * alpha - beta, alpha}, R_, f);  // definite: no zero pivot
      for (int r = 0; r < R_; ++r) {
        inv_d_(r, q) = 1 / f.d[r];
        if (r + 1 < R_) l1_(r, q) = f.l1[r];
        if (r + 2 < R_) l2_(r, q) = f.l2[r];
      }
    }
  }

  // The four capacitance blocks (parity of q) × (parity of p), see the header.
  void build_capacitance() {
    const double a = weights_.a, b = weights_.b;
    const Eigen::VectorXd mu = second_difference_eigenvalues(R_);
    const Eigen::VectorXd sigma = std::sqrt(2.0) * first_sine_column(R_);
    t_ = std::sqrt(2.0) * first_sine_column(C_);
    const auto lambda = [&](int p, int q) {
      const double s = mu[p] + nu_[q];
      return a * mu[p] * mu[p] * nu_[q] * nu_[q] + b * s * s;
    };
    for (int qpar = 0; qpar < 2; ++qpar) {
      std::vector<int> qs;
      for (int q = qpar; q < C_; q += 2) qs.push_back(q);
      for (int ppar = 0; ppar < 2; ++ppar) {
        CapacitanceBlock& blk = blocks_[2 * std::size_t(qpar) + std::size_t(ppar)];
        blk.modes.clear();
        for (int p = ppar; p < R_; p += 2) blk.modes.push_back(p);
        const auto n = Eigen::Index(blk.modes.size());
        blk.diag.resize(n);
        blk.u.resize(n);
        blk.G.resize(n, Eigen::Index(qs.size()));
        double su = 0;
        for (Eigen::Index k = 0; k < n; ++k) {
          const int p = blk.modes[std::size_t(k)];
          const double dl = a * mu[p] * mu[p] + b;  // H = a·P_i + b·I = S(aμ² + b)S + a·E_i
          blk.u[k] = sigma[p] / dl;
          blk.diag[k] = 1 / dl;
          su += sigma[p] * blk.u[k];
        }
        blk.kappa = a / (1 + a * su);
        for (std::size_t k = 0; k < qs.size(); ++k) {
          const int q = qs[k];
          const double alpha = a * nu_[q] * nu_[q] + b;  // the weight of E_i in M_q
          double gamma = 0;
          for (Eigen::Index m = 0; m < n; ++m) {
            const int p = blk.modes[std::size_t(m)];
            gamma += sigma[p] * sigma[p] / lambda(p, q);
          }
          const double c = std::sqrt(t_[q] * t_[q] * alpha / (1 + alpha * gamma));
          for (Eigen::Index m = 0; m < n; ++m) {
            const int p = blk.modes[std::size_t(m)];
            const double l = lambda(p, q);
            blk.diag[m] += t_[q] * t_[q] / l;
            blk.G(m, Eigen::Index(k)) = c * sigma[p] / l;
          }
        }
      }
    }
  }

  // Y = A X for one grid: A = a·P⊗P + b·(P⊗I + 2·D⊗D + I⊗P), the 1-D operators applied along j
  // within each row (U = X P, V = X D), then along i as combinations of rows.
  void apply_operator(const Eigen::Map<RowMajor>& X, RowMajor& Y) {
    const double a = weights_.a, b = weights_.b;
    const auto along_j = [&](RowMajor& Z, double c0, double c1, double c2) {
      Z = c0 * X;
      if (C_ > 1) {
        Z.rightCols(C_ - 1) += c1 * X.leftCols(C_ - 1);
        Z.leftCols(C_ - 1) += c1 * X.rightCols(C_ - 1);
      }
      if (C_ > 2 && c2 != 0) {
        Z.rightCols(C_ - 2) += c2 * X.leftCols(C_ - 2);
        Z.leftCols(C_ - 2) += c2 * X.rightCols(C_ - 2);
      }
    };
    along_j(u_, 6, -4, 1);
    along_j(v_, 2, -1, 0);
    Y = b * u_;
    const auto add_along_i = [&](const auto& Z, double scale, double c0, double c1, double c2) {
      if (scale == 0) return;
      for (int r = 0; r < R_; ++r) {
        Y.row(r) += (scale * c0) * Z.row(r);
        if (r >= 1) Y.row(r) += (scale * c1) * Z.row(r - 1);
        if (r + 1 < R_) Y.row(r) += (scale * c1) * Z.row(r + 1);
        if (c2 == 0) continue;
        if (r >= 2) Y.row(r) += (scale * c2) * Z.row(r - 2);
        if (r + 2 < R_) Y.row(r) += (scale * c2) * Z.row(r + 2);
      }
    };
    add_along_i(u_, a, 6, -4, 1);
    add_along_i(X, b, 6, -4, 1);
    add_along_i(v_, 2 * b, 2, -1, 0);
  }

  // Y ← M_q⁻¹ Y for every mode q (Y rows × cols, row-major).
  void banded_solve(RowMajor& Y) const {
    for (int r = 1; r < R_; ++r) {
      Y.row(r).array() -= l1_.row(r - 1).array() * Y.row(r - 1).array();
      if (r >= 2) Y.row(r).array() -= l2_.row(r - 2).array() * Y.row(r - 2).array();
    }
    Y.row(R_ - 1).array() *= inv_d_.row(R_ - 1).array();
    for (int r = R_ - 2; r >= 0; --r) {
      Y.row(r).array() = Y.row(r).array() * inv_d_.row(r).array() - l1_.row(r).array() * Y.row(r + 1).array();
      if (r + 2 < R_) Y.row(r).array() -= l2_.row(r).array() * Y.row(r + 2).array();
    }
  }

  // count right-hand sides (row-major grids) to their solutions; the capacitance systems of all
  // of them are solved together (one read of each block per iteration). Returns the iterations.
  int solve_columns(const std::array<const double*, 3>& b, const std::array<double*, 3>& x, int count) {
    const double scale_j = std::sqrt(2.0 / (C_ + 1)), scale_i = std::sqrt(2.0 / (R_ + 1));
    Eigen::MatrixXd tmasks = Eigen::MatrixXd::Zero(C_, 2), g2(R_, 2), h2(R_, 2);  // t_q on the modes of each parity
    std::array<Eigen::MatrixXd, 2> ghat, hhat;
    for (int qpar = 0; qpar < 2; ++qpar) {
      for (int q = qpar; q < C_; q += 2) tmasks(q, qpar) = t_[q];
      ghat[std::size_t(qpar)].resize(R_, count);
      hhat[std::size_t(qpar)].setZero(R_, count);
    }
    for (int c = 0; c < count; ++c) {
      RowMajor& hat = hats_[std::size_t(c)];
      hat.resize(R_, C_);
      for (int r = 0; r < R_; ++r) along_j_.apply(b[std::size_t(c)] + std::ptrdiff_t(r) * C_, &hat(r, 0), scale_j);
      y_ = hat;
      banded_solve(y_);
      g2.noalias() = y_ * tmasks;  // both parities in one pass over the grid
      for (int qpar = 0; qpar < 2; ++qpar)
        along_i_.apply(g2.col(qpar).data(), ghat[std::size_t(qpar)].col(c).data(), scale_i);
    }
    int iterations = 0;
    Eigen::MatrixXd rhs, part;
    for (int qpar = 0; qpar < 2; ++qpar)
      for (int ppar = 0; ppar < 2; ++ppar) {
        const CapacitanceBlock& blk = blocks_[2 * std::size_t(qpar) + std::size_t(ppar)];
        rhs.resize(Eigen::Index(blk.modes.size()), count);
        for (std::size_t k = 0; k < blk.modes.size(); ++k)
          rhs.row(Eigen::Index(k)) = ghat[std::size_t(qpar)].row(blk.modes[k]);
        iterations = std::max(iterations, blk.solve(rhs, part));
        for (std::size_t k = 0; k < blk.modes.size(); ++k)
          hhat[std::size_t(qpar)].row(blk.modes[k]) = part.row(Eigen::Index(k));
      }
    for (int c = 0; c < count; ++c) {
      RowMajor& hat = hats_[std::size_t(c)];
      for (int qpar = 0; qpar < 2; ++qpar)
        along_i_.apply(hhat[std::size_t(qpar)].col(c).data(), h2.col(qpar).data(), scale_i);
      hat.noalias() -= h2 * tmasks.transpose();  // a rank-two update, one pass
      banded_solve(hat);
      for (int r = 0; r < R_; ++r) along_j_.apply(&hat(r, 0), x[std::size_t(c)] + std::ptrdiff_t(r) * C_, scale_j);
    }
    return iterations;
  }

  int R_ = 0, C_ = 0;
  C1FamilyWeights weights_;
  bool separable_ = false;
  detail::SineTransform along_i_, along_j_;
  Eigen::VectorXd nu_, t_;
  RowMajor inv_d_, l1_, l2_;
  std::array<CapacitanceBlock, 4> blocks_;
  RowMajor y_, u_, v_;  // scratch
  std::array<RowMajor, 3> hats_, residuals_, corrections_;
  std::array<int, 3> targets_{};
};

}  // namespace

std::optional<C1FamilyWeights> c1_family_weights(const StencilOperator& op) {
  if (op.radius != 2 || op.weights.size() != 25) return std::nullopt;
  double scale = 0;
  for (double w : op.weights) scale = std::max(scale, std::abs(w));
  if (!(scale > 0)) return std::nullopt;
  C1FamilyWeights w;
  w.a = op.weight(2, 2);
  w.b = op.weight(2, 0) - 6 * w.a;
  const double tol = 1e-12 * scale;
  for (int di = -2; di <= 2; ++di)
    for (int dj = -2; dj <= 2; ++dj)
      if (std::abs(op.weight(di, dj) - (w.a * c_weight(di, dj) + w.b * t_weight(di, dj))) > tol) return std::nullopt;
  if (w.a < -tol || w.b < -tol) return std::nullopt;
  w.a = std::max(w.a, 0.0);
  w.b = std::max(w.b, 0.0);
  if (!(w.a + w.b > 0)) return std::nullopt;
  return w;
}

std::unique_ptr<LinearSolver> make_fast5_solver(const SolverOptions& options) {
  return std::make_unique<Fast5Solver>(options);
}

}  // namespace coons::solvers
