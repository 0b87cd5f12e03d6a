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

  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
    out = diag.cwiseProduct(v) - (kappa * u.dot(v)) * u - G * (G.transpose() * v);
  }

  // Conjugate gradients with the diagonal as preconditioner; returns the iterations.
  int solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) const {
    const Eigen::Index n = rhs.size();
    x.setZero(n);
    const double target = kCapacitanceTolerance * rhs.norm();
    if (n == 0 || !(target > 0)) return 0;
    Eigen::VectorXd r = rhs, z = r.cwiseQuotient(diag), p = z, Ap;
    double rz = r.dot(z);
    const int limit = int(2 * n + 50);
    for (int k = 1; k <= limit; ++k) {
      apply(p, Ap);
      const double step = rz / p.dot(Ap);
      x += step * p;
      r -= step * Ap;
      if (r.norm() <= target) return k;
      z = r.cwiseQuotient(diag);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
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
  std::string why;
  if (!g.is_valid(&why)) {
    summary.message = "invalid grid operator: " + why;
    return false;
  }
  if (g.size() != Eigen::Index(g.rows) * g.cols) {
    summary.message = "needs a full rectangle (every grid point free); use pcg-fast for other free sets";
    return false;
  }
  if (op.matrix && op.matrix->rows() != g.size()) {
    summary.message = "the matrix and the grid operator differ in size";
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
    int iterations = 0;
    for (int c = 0; c < 3; ++c) {
      iterations = std::max(iterations, solve_column(B.col(c).data(), X.col(c).data()));
      // The capacitance operator is formed from differences of large terms (the sine-basis
      // inverses of the modes next to the corner cancel), so the first solve loses digits that
      // grow with N; iterative refinement on the true residual (O(rows·cols)) restores them.
      const Eigen::Map<const RowMajor> b(B.col(c).data(), R_, C_);
      Eigen::Map<RowMajor> x(X.col(c).data(), R_, C_);
      const double norm_b = b.norm();
      for (int k = 0; k < kRefinements; ++k) {
        apply_operator(x, residual_);
        residual_ = b - residual_;
        if (!(residual_.norm() > kRefinedResidual * norm_b)) break;
        correction_.resize(R_, C_);
        iterations = std::max(iterations, solve_column(residual_.data(), correction_.data()));
        x += correction_;
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

  // One right-hand side (a row-major grid) to one solution; returns the capacitance iterations.
  int solve_column(const double* b, double* x) {
    const double scale_j = std::sqrt(2.0 / (C_ + 1)), scale_i = std::sqrt(2.0 / (R_ + 1));
    hat_.resize(R_, C_);
    for (int r = 0; r < R_; ++r) along_j_.apply(b + std::ptrdiff_t(r) * C_, &hat_(r, 0), scale_j);
    y_ = hat_;
    banded_solve(y_);
    int iterations = 0;
    Eigen::VectorXd g, ghat(R_), hhat(R_), h(R_), part;
    for (int qpar = 0; qpar < 2; ++qpar) {
      Eigen::VectorXd tmask = Eigen::VectorXd::Zero(C_);
      for (int q = qpar; q < C_; q += 2) tmask[q] = t_[q];
      g = y_ * tmask;
      along_i_.apply(g.data(), ghat.data(), scale_i);
      hhat.setZero();
      for (int ppar = 0; ppar < 2; ++ppar) {
        const CapacitanceBlock& blk = blocks_[2 * std::size_t(qpar) + std::size_t(ppar)];
        Eigen::VectorXd rhs(Eigen::Index(blk.modes.size()));
        for (std::size_t k = 0; k < blk.modes.size(); ++k) rhs[Eigen::Index(k)] = ghat[blk.modes[k]];
        iterations = std::max(iterations, blk.solve(rhs, part));
        for (std::size_t k = 0; k < blk.modes.size(); ++k) hhat[blk.modes[k]] = part[Eigen::Index(k)];
      }
      along_i_.apply(hhat.data(), h.data(), scale_i);
      hat_.noalias() -= h * tmask.transpose();
    }
    banded_solve(hat_);
    for (int r = 0; r < R_; ++r) along_j_.apply(&hat_(r, 0), x + std::ptrdiff_t(r) * C_, scale_j);
    return iterations;
  }

  int R_ = 0, C_ = 0;
  C1FamilyWeights weights_;
  bool separable_ = false;
  detail::SineTransform along_i_, along_j_;
  Eigen::VectorXd nu_, t_;
  RowMajor inv_d_, l1_, l2_;
  std::array<CapacitanceBlock, 4> blocks_;
  RowMajor hat_, y_, u_, v_, residual_, correction_;  // scratch
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
