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
constexpr int kCorrections = 3;              // at most this many boundary corrections per solve
constexpr double kBoundaryResidual = 1e-13;  // relative residual on the boundary columns at which they stop

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
//   Cap·v = diag ⊙ v − kappa·u (uᵀv) − G (Gᵀv),   symmetric positive definite,
// and of H⁻¹ (H = a·P_i + b·I) in the same basis: h_inv ⊙ v − kappa·u (uᵀv).
struct CapacitanceBlock {
  std::vector<int> modes;  // modes p (0-based) along i of this block
  Eigen::VectorXd diag, h_inv, u;
  double kappa = 0;
  Eigen::MatrixXd G;  // #modes by #(modes q of the column parity), column-major

  // out = Cap·V. G is read twice, a column at a time, for all right-hand sides together
  // (hand-written: Eigen's product would pack G into a copy on every call).
  void apply(const Eigen::MatrixXd& V, Eigen::MatrixXd& out, Eigen::MatrixXd& s) const {
    const Eigen::Index m = V.cols();
    out.noalias() = diag.asDiagonal() * V;
    out.noalias() -= (kappa * u) * (u.transpose() * V);
    s.resize(G.cols(), m);
    for (Eigen::Index k = 0; k < G.cols(); ++k)
      for (Eigen::Index c = 0; c < m; ++c) s(k, c) = G.col(k).dot(V.col(c));
    for (Eigen::Index k = 0; k < G.cols(); ++k)
      for (Eigen::Index c = 0; c < m; ++c) out.col(c) -= s(k, c) * G.col(k);
  }

  // V ← H⁻¹ V (rows of V are this block's modes).
  void apply_h_inverse(Eigen::MatrixXd& V) const {
    const Eigen::RowVectorXd uv = u.transpose() * V;
    V = h_inv.asDiagonal() * V;
    V.noalias() -= (kappa * u) * uv;
  }

  // Conjugate gradients with the diagonal as preconditioner, one column per right-hand side
  // (each with its own step lengths; a converged column is frozen); returns the iterations.
  int solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& X) const {
    const Eigen::Index n = rhs.rows(), m = rhs.cols();
    X.setZero(n, m);
    if (n == 0 || m == 0) return 0;
    Eigen::ArrayXd target = kCapacitanceTolerance * rhs.colwise().norm().transpose().array();
    Eigen::MatrixXd R = rhs, Z = diag.cwiseInverse().asDiagonal() * R, P = Z, AP, s;
    Eigen::ArrayXd rz = (R.cwiseProduct(Z)).colwise().sum().transpose().array();
    std::vector<bool> active(static_cast<std::size_t>(m), false);
    for (Eigen::Index c = 0; c < m; ++c) active[std::size_t(c)] = target[c] > 0;
    const int limit = int(2 * n + 50);
    for (int k = 1; k <= limit; ++k) {
      apply(P, AP, s);
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
    const int count = 3;
    const double scale_j = std::sqrt(2.0 / (C_ + 1));
    for (int c = 0; c < count; ++c) {
      RowMajor& hat = hats_[std::size_t(c)];
      hat.resize(R_, C_);
      for (int r = 0; r < R_; ++r) along_j_.apply(B.col(c).data() + std::ptrdiff_t(r) * C_, &hat(r, 0), scale_j);
    }
    // ŷ = A₁⁻¹ b̂ and its boundary columns g (both parities); h = Cap⁻¹ g; x̂ = ŷ − A₁⁻¹ U h.
    banded_solve_all(count, dots_);
    std::array<Eigen::MatrixXd, 2> h;
    int iterations = capacitance_solve(dots_, count, false, h);
    add_boundary_response(count, h, -1.0, true);
    // The columns 0 and cols−1 carry the rounding of h (see the header): correct them from the
    // residual there, which is exact, until it is below kBoundaryResidual relative to b.
    std::array<Eigen::MatrixXd, 2> rho;
    for (int step = 0; step < kCorrections; ++step) {
      if (!boundary_residual(B, count, rho)) break;
      iterations = std::max(iterations, capacitance_solve(rho, count, true, h));
      add_boundary_response(count, h, 1.0, false);
    }
    X.resize(B.rows(), 3);
    for (int c = 0; c < count; ++c) {
      RowMajor& hat = hats_[std::size_t(c)];
      for (int r = 0; r < R_; ++r) along_j_.apply(&hat(r, 0), X.col(c).data() + std::ptrdiff_t(r) * C_, scale_j);
    }
    summary.iterations = iterations;
    return SolveStatus::kSuccess;
  }

 private:
  // The banded LDLᵀ of M_q = (aν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I for every mode q along j,
  // stored row-major by (row r, mode q), computed a row at a time for all modes together.
  void factor_modes() {
    const double a = weights_.a, b = weights_.b;
    nu_ = second_difference_eigenvalues(C_);
    inv_d_.resize(R_, C_);
    l1_.setZero(R_, C_);
    l2_.setZero(R_, C_);
    Eigen::ArrayXd d0(C_), d1(C_), d2(C_), dprev(C_), dprev2(C_), d(C_);
    for (int q = 0; q < C_; ++q) {
      const double alpha = a * nu_[q] * nu_[q] + b, beta = 2 * b * nu_[q], gamma = b * nu_[q] * nu_[q];
      d0[q] = 6 * alpha + 2 * beta + gamma;  // definite: no zero pivot
      d1[q] = -4 * alpha - beta;
      d2[q] = alpha;
    }
    for (int r = 0; r < R_; ++r) {
      d = d0;
      if (r >= 1) d -= l1_.row(r - 1).transpose().array().square() * dprev;
      if (r >= 2) d -= l2_.row(r - 2).transpose().array().square() * dprev2;
      inv_d_.row(r) = d.inverse().transpose();
      if (r + 1 < R_) {
        Eigen::ArrayXd l = d1;
        if (r >= 1) l -= l2_.row(r - 1).transpose().array() * dprev * l1_.row(r - 1).transpose().array();
        l1_.row(r) = (l / d).transpose();
      }
      if (r + 2 < R_) l2_.row(r) = (d2 / d).transpose();
      dprev2 = dprev;
      dprev = d;
    }
  }

  // The four capacitance blocks (parity of q) × (parity of p), see the header, and the sine
  // vectors of the grid columns next to the boundary (for the boundary residual).
  void build_capacitance() {
    const double a = weights_.a, b = weights_.b;
    const Eigen::VectorXd mu = second_difference_eigenvalues(R_);
    const Eigen::VectorXd sigma = std::sqrt(2.0) * first_sine_column(R_);
    t_ = std::sqrt(2.0) * first_sine_column(C_);
    tmasks_.setZero(C_, 2);  // t_q on the modes of each parity
    for (int q = 0; q < C_; ++q) tmasks_(q, q % 2) = t_[q];
    near_.clear();  // columns 0, 1, 2, cols−3, cols−2, cols−1
    for (int j : {0, 1, 2, C_ - 3, C_ - 2, C_ - 1})
      if (j >= 0 && j < C_ && std::find(near_.begin(), near_.end(), j) == near_.end()) near_.push_back(j);
    near_sines_.resize(C_, Eigen::Index(near_.size()));
    for (std::size_t k = 0; k < near_.size(); ++k)
      for (int q = 0; q < C_; ++q)
        near_sines_(q, Eigen::Index(k)) = std::sqrt(2.0 / (C_ + 1)) * std::sin(M_PI * (near_[k] + 1) * (q + 1) / (C_ + 1));
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
        blk.h_inv.resize(n);
        blk.u.resize(n);
        blk.G.resize(n, Eigen::Index(qs.size()));
        double su = 0;
        for (Eigen::Index k = 0; k < n; ++k) {
          const int p = blk.modes[std::size_t(k)];
          const double dl = a * mu[p] * mu[p] + b;  // H = a·P_i + b·I = S(aμ² + b)S + a·E_i
          blk.u[k] = sigma[p] / dl;
          blk.h_inv[k] = 1 / dl;
          su += sigma[p] * blk.u[k];
        }
        blk.diag = blk.h_inv;
        blk.kappa = a / (1 + a * su);
        Eigen::VectorXd inv_lambda(n);
        for (std::size_t k = 0; k < qs.size(); ++k) {
          const int q = qs[k];
          const double alpha = a * nu_[q] * nu_[q] + b;  // the weight of E_i in M_q
          double gamma = 0;
          for (Eigen::Index m = 0; m < n; ++m) {
            const int p = blk.modes[std::size_t(m)];
            inv_lambda[m] = 1 / lambda(p, q);
            gamma += sigma[p] * sigma[p] * inv_lambda[m];
          }
          const double c = std::sqrt(t_[q] * t_[q] * alpha / (1 + alpha * gamma));
          for (Eigen::Index m = 0; m < n; ++m) {
            const int p = blk.modes[std::size_t(m)];
            blk.diag[m] += t_[q] * t_[q] * inv_lambda[m];
            blk.G(m, Eigen::Index(k)) = c * sigma[p] * inv_lambda[m];
          }
        }
      }
    }
  }

  // work_[c] = M⁻¹ hats_[c] for every mode q (rows × cols, row-major), all right-hand sides in
  // one sweep down and one up (each factor row read once for all of them); g(r, 2c + parity) =
  // Σ_q (M⁻¹ hat)(r, q)·t_q over the modes q of that parity.
  void banded_solve_all(int count, Eigen::MatrixXd& g) {
    g.resize(R_, 2 * count);
    for (int c = 0; c < count; ++c) work_[std::size_t(c)].resize(R_, C_);
    for (int r = 0; r < R_; ++r)
      for (int c = 0; c < count; ++c) {
        RowMajor& W = work_[std::size_t(c)];
        const RowMajor& Y = hats_[std::size_t(c)];
        if (r == 0) {
          W.row(r) = Y.row(r);
        } else if (r == 1) {
          W.row(r).array() = Y.row(r).array() - l1_.row(r - 1).array() * W.row(r - 1).array();
        } else {
          W.row(r).array() = Y.row(r).array() - l1_.row(r - 1).array() * W.row(r - 1).array() -
                             l2_.row(r - 2).array() * W.row(r - 2).array();
        }
      }
    backward_sweep(count, g, tmasks_, nullptr);
  }

  // The sweep up of the banded solve on work_[c] (already swept down); out(r, ·) = row r of the
  // result times `dots` (one row per mode); with add, hats_[c] += the result and out is taken of
  // the sum.
  void backward_sweep(int count, Eigen::MatrixXd& out, const Eigen::MatrixXd& dots, bool* add) {
    const Eigen::Index k = dots.cols();
    out.resize(R_, k * count);
    for (int r = R_ - 1; r >= 0; --r)
      for (int c = 0; c < count; ++c) {
        RowMajor& W = work_[std::size_t(c)];
        if (r + 1 < R_) {
          W.row(r).array() = W.row(r).array() * inv_d_.row(r).array() - l1_.row(r).array() * W.row(r + 1).array();
        } else {
          W.row(r).array() *= inv_d_.row(r).array();
        }
        if (r + 2 < R_) W.row(r).array() -= l2_.row(r).array() * W.row(r + 2).array();
        if (add) {
          RowMajor& Y = hats_[std::size_t(c)];
          Y.row(r) += W.row(r);
          out.block(r, k * c, 1, k).noalias() = Y.row(r) * dots;
        } else {
          out.block(r, k * c, 1, k).noalias() = W.row(r) * dots;
        }
      }
  }

  // With replace: hats_[c] ← M⁻¹(hats_[c] + sign·U z_c); otherwise hats_[c] += sign·M⁻¹ U z_c, the
  // response to sources z on the boundary columns (parity coordinates: (U z)(r, q) = t_q z(r, parity
  // of q) in the sine basis along j). near_values_[c] = the result on the columns near_.
  void add_boundary_response(int count, const std::array<Eigen::MatrixXd, 2>& z, double sign, bool replace) {
    for (int c = 0; c < count; ++c) work_[std::size_t(c)].resize(R_, C_);
    for (int r = 0; r < R_; ++r)
      for (int c = 0; c < count; ++c) {
        RowMajor& W = work_[std::size_t(c)];
        if (replace) {
          W.row(r) = hats_[std::size_t(c)].row(r);
          W.row(r).noalias() += (sign * z[0](r, c)) * tmasks_.col(0).transpose();
        } else {
          W.row(r).noalias() = (sign * z[0](r, c)) * tmasks_.col(0).transpose();
        }
        W.row(r).noalias() += (sign * z[1](r, c)) * tmasks_.col(1).transpose();
        if (r >= 1) W.row(r).array() -= l1_.row(r - 1).array() * W.row(r - 1).array();
        if (r >= 2) W.row(r).array() -= l2_.row(r - 2).array() * W.row(r - 2).array();
      }
    if (replace) {
      backward_sweep(count, near_values_, near_sines_, nullptr);
      for (int c = 0; c < count; ++c) std::swap(hats_[std::size_t(c)], work_[std::size_t(c)]);
    } else {
      bool add = true;
      backward_sweep(count, near_values_, near_sines_, &add);
    }
  }

  // The capacitance system for each parity of q: rhs[qpar] is rows × count in the grid (along i);
  // with apply_h the right-hand side is H⁻¹·rhs. out[qpar] = Cap⁻¹ (H⁻¹) rhs, the same shape.
  int capacitance_solve(const Eigen::MatrixXd& g, int count, bool apply_h, std::array<Eigen::MatrixXd, 2>& out) {
    std::array<Eigen::MatrixXd, 2> rhs;
    for (int qpar = 0; qpar < 2; ++qpar) {
      rhs[std::size_t(qpar)].resize(R_, count);
      for (int c = 0; c < count; ++c) rhs[std::size_t(qpar)].col(c) = g.col(2 * c + qpar);
    }
    return capacitance_solve(rhs, count, apply_h, out);
  }

  int capacitance_solve(const std::array<Eigen::MatrixXd, 2>& rhs, int count, bool apply_h,
                        std::array<Eigen::MatrixXd, 2>& out) {
    const double scale_i = std::sqrt(2.0 / (R_ + 1));
    Eigen::MatrixXd hat(R_, count), part, block_rhs;
    Eigen::VectorXd column(R_);
    int iterations = 0;
    for (int qpar = 0; qpar < 2; ++qpar) {
      for (int c = 0; c < count; ++c) {
        column = rhs[std::size_t(qpar)].col(c);
        along_i_.apply(column.data(), hat.col(c).data(), scale_i);
      }
      Eigen::MatrixXd solved(R_, count);
      for (int ppar = 0; ppar < 2; ++ppar) {
        const CapacitanceBlock& blk = blocks_[2 * std::size_t(qpar) + std::size_t(ppar)];
        block_rhs.resize(Eigen::Index(blk.modes.size()), count);
        for (std::size_t k = 0; k < blk.modes.size(); ++k) block_rhs.row(Eigen::Index(k)) = hat.row(blk.modes[k]);
        if (apply_h) blk.apply_h_inverse(block_rhs);
        iterations = std::max(iterations, blk.solve(block_rhs, part));
        for (std::size_t k = 0; k < blk.modes.size(); ++k) solved.row(blk.modes[k]) = part.row(Eigen::Index(k));
      }
      out[std::size_t(qpar)].resize(R_, count);
      for (int c = 0; c < count; ++c) {
        column = solved.col(c);
        along_i_.apply(column.data(), out[std::size_t(qpar)].col(c).data(), scale_i);
      }
    }
    return iterations;
  }

  // ρ = (b − A x) on the columns 0 and cols−1 in parity coordinates (rows × count each), x from
  // near_values_; false when it is below kBoundaryResidual·‖b‖ for every right-hand side.
  bool boundary_residual(const Eigen::MatrixX3d& B, int count, std::array<Eigen::MatrixXd, 2>& rho) {
    const double a = weights_.a, b = weights_.b;
    std::array<Eigen::MatrixXd, 2> side;  // the residual on column 0 and on column cols−1
    bool large = false;
    for (int s = 0; s < 2; ++s) side[std::size_t(s)].resize(R_, count);
    for (int c = 0; c < count; ++c) {
      const auto value = [&](int i, int j) {
        if (i < 0 || i >= R_ || j < 0 || j >= C_) return 0.0;
        const auto k = std::find(near_.begin(), near_.end(), j) - near_.begin();
        return near_values_(i, Eigen::Index(near_.size()) * c + k);
      };
      double norm2 = 0;
      for (int s = 0; s < 2; ++s) {
        const int j = s == 0 ? 0 : C_ - 1;
        for (int i = 0; i < R_; ++i) {
          double r = B(Eigen::Index(i) * C_ + j, c);
          for (int di = -2; di <= 2; ++di)
            for (int dj = -2; dj <= 2; ++dj) r -= (a * c_weight(di, dj) + b * t_weight(di, dj)) * value(i + di, j + dj);
          side[std::size_t(s)](i, c) = r;
        }
        norm2 += side[std::size_t(s)].col(c).squaredNorm();
      }
      if (std::sqrt(norm2) > kBoundaryResidual * B.col(c).norm()) large = true;
    }
    if (!large) return false;
    for (int s = 0; s < 2; ++s) rho[std::size_t(s)].resize(R_, count);
    if (C_ == 1) {  // U = √2·e₁ in the even parity
      rho[0] = side[0] / std::sqrt(2.0);
      rho[1].setZero();
    } else {
      rho[0] = (side[0] + side[1]) / std::sqrt(2.0);
      rho[1] = (side[0] - side[1]) / std::sqrt(2.0);
    }
    return true;
  }

  int R_ = 0, C_ = 0;
  C1FamilyWeights weights_;
  bool separable_ = false;
  detail::SineTransform along_i_, along_j_;
  Eigen::VectorXd nu_, t_;
  Eigen::MatrixXd tmasks_, near_sines_, dots_;
  std::vector<int> near_;
  RowMajor inv_d_, l1_, l2_;
  std::array<CapacitanceBlock, 4> blocks_;
  std::array<RowMajor, 3> hats_, work_;
  Eigen::MatrixXd near_values_;  // rows × (#near_ · count)
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
