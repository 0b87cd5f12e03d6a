#include "spectral_objective.h"

#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

#include "solvers/sine_basis.h"
#include "solvers/vector_clones.h"

namespace coons {

namespace {

// The sides of the frame as frame_net reads them (corners from bottom and top): along i the
// columns j = 0 and j = n, along j the rows i = 0 and i = m; each #len+1 by 3.
struct Sides {
  Eigen::MatrixX3d bottom, top, left, right;
};
Sides frame_sides(const Boundary& b) {
  Sides s{b.bottom, b.top, b.left, b.right};
  s.left.row(0) = b.bottom.row(0);
  s.left.row(b.n) = b.top.row(0);
  s.right.row(0) = b.bottom.row(b.m);
  s.right.row(b.n) = b.top.row(b.m);
  return s;
}

// D^order F: forward differences of the columns (#rows − order rows).
Eigen::MatrixXd differences(Eigen::MatrixXd F, int order) {
  for (int k = 0; k < order; ++k) F = (F.bottomRows(F.rows() - 1) - F.topRows(F.rows() - 1)).eval();
  return F;
}

// (D^order)ᵀ D^order F at the interior points 1..len−1 of columns F (#len+1 rows): half the
// gradient of Σ‖D^order f‖² there.
Eigen::MatrixXd normal_interior(const Eigen::MatrixXd& F, int order) {
  Eigen::MatrixXd d = differences(F, order);
  for (int k = 0; k < order; ++k) {  // the adjoint of one forward difference
    Eigen::MatrixXd up = Eigen::MatrixXd::Zero(d.rows() + 1, d.cols());
    up.bottomRows(d.rows()) += d;
    up.topRows(d.rows()) -= d;
    d = std::move(up);
  }
  return d.middleRows(1, F.rows() - 2);
}

// Σ over a grid of (Σ_t A(i, t)·B(j, t))² = Σ_{t,s} (AᵀA)_ts (BᵀB)_ts.
double separable_square_sum(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return ((A.transpose() * A).array() * (B.transpose() * B).array()).sum();
}

// One row p of modes: per coordinate R̂(p, q) = r_b(p)·L̂0(q) + r_t(p)·L̂1(q) + l̂0(p)·r_l(q) + l̂1(p)·r_r(q),
// ĉ likewise; quad = symbol·Σ R̂², lin = 2·Σ ĉ·R̂. `u` is row p of the i-direction factors, V the
// j-direction factors (#cols by 14, column-major; layout in the constructor).
COONS_VECTOR_CLONES void mode_row(const double* __restrict u, const double* __restrict V, int cols,
                                  const double* __restrict symbol, double* __restrict quad, double* __restrict lin) {
  const double* __restrict l0 = V + std::ptrdiff_t(12) * cols;
  const double* __restrict l1 = V + std::ptrdiff_t(13) * cols;
  for (int q = 0; q < cols; ++q) {
    double rr = 0, cr = 0;
    for (int k = 0; k < 3; ++k) {
      const double r = u[k] * l0[q] + u[3 + k] * l1[q] + u[12] * V[std::ptrdiff_t(k) * cols + q] +
                       u[13] * V[std::ptrdiff_t(3 + k) * cols + q];
      const double c = u[6 + k] * l0[q] + u[9 + k] * l1[q] + u[12] * V[std::ptrdiff_t(6 + k) * cols + q] +
                       u[13] * V[std::ptrdiff_t(9 + k) * cols + q];
      rr += r * r;
      cr += c * r;
    }
    quad[q] = symbol[q] * rr;
    lin[q] = 2 * cr;
  }
}

// Σ over the modes of f, f', f'' and min |λ| (see evaluate); one pass over two arrays.
struct ModeSums {
  double f = 0, df = 0, d2f = 0, df_abs = 0, smallest = HUGE_VAL;
};
COONS_VECTOR_CLONES ModeSums mode_sums(double alpha, const double* __restrict xi, int rows, const double* __restrict eta,
                                       int cols, const double* __restrict quad, const double* __restrict lin) {
  const double gamma = alpha + 0.25;
  ModeSums total;
  for (int p = 0; p < rows; ++p) {
    double f = 0, df = 0, d2f = 0, df_abs = 0, smallest = HUGE_VAL;
    const double xp = xi[p];
    const double* __restrict qr = quad + std::ptrdiff_t(p) * cols;
    const double* __restrict lr = lin + std::ptrdiff_t(p) * cols;
#pragma omp simd reduction(+ : f, df, d2f, df_abs) reduction(min : smallest)
    for (int q = 0; q < cols; ++q) {
      // λ = λ_C + γ·d with λ_C = ξη (the Coons eigenvalue) and d = 2(ξ + η − 2ξη), in ξ = 1 − x,
      // η = 1 − y: no cancellation for the low modes. δ̂ = u·R̂ with u = γ/λ, u' = λ_C/λ².
      const double lc = xp * eta[q], d = 2 * (xp + eta[q] - 2 * lc);
      const double lambda = lc + gamma * d, il = 1 / lambda;
      const double u = gamma * il, du = lc * il * il, d2u = -2 * du * d * il;
      const double w = 2 * qr[q] * u + lr[q];  // ∂f/∂u of the mode
      f += u * (qr[q] * u + lr[q]);
      df += w * du;
      df_abs += (std::abs(2 * qr[q] * u) + std::abs(lr[q])) * std::abs(du);
      d2f += 2 * qr[q] * du * du + w * d2u;
      smallest = std::min(smallest, std::abs(lambda));
    }
    total.f += f;
    total.df += df;
    total.d2f += d2f;
    total.df_abs += df_abs;
    total.smallest = std::min(total.smallest, smallest);
  }
  return total;
}

}  // namespace

SpectralAlphaObjective::SpectralAlphaObjective(const Boundary& b, std::vector<std::pair<DiscreteEnergy, double>> terms)
    : rows_(b.m - 1), cols_(b.n - 1), terms_(std::move(terms)) {
  assert(rows_ >= 1 && cols_ >= 1 && !terms_.empty());
  // Measured from the discrete Coons net N_C (the α = −1/4 solution): N(α) = N_C + δ(α) with
  // A(α) δ = (α + 1/4)·R, R the 5-point Laplacian of N_C. Then f = E(N_C) + 2 c·δ + E(δ), c the
  // halved gradient of E at N_C: only small terms, no cancellation against the energy of the frame.
  //
  // N_C is a boolean sum of linear blends, per coordinate A·Bᵀ of rank 4:
  //   A = [1 − i/m, i/m, bottom(i), top(i)],  B = [left′(j), right′(j), 1 − j/n, j/n]
  // (left′ = left minus the linear blend of its end points). Each energy is Σ w‖Δ_i^a Δ_j^b N‖²
  // (difference_terms), whose Hessian is w·(K_a ⊗ K_b), K_a = (D^a)ᵀD^a. Hence, with K_1, K_2 of a
  // linear column vanishing at the interior points:
  //   E(N_C) = Σ w Σ_xyz ⟨(D^a A)ᵀ(D^a A), (D^b B)ᵀ(D^b B)⟩
  //   R = −K_1 bottom ⊗ (1 − j/n) − K_1 top ⊗ j/n − (1 − i/m) ⊗ K_1 left′ − i/m ⊗ K_1 right′
  //   c = Σ_{b=0} w K_a bottom ⊗ (1 − j/n) + … + Σ_{a=0} w (1 − i/m) ⊗ K_b left′ + …
  // (terms with a, b ≥ 1 leave nothing inside: the Coons net minimises the discrete twist). The 2-D
  // sine transform of u ⊗ v is û ⊗ v̂: the set-up is O(N log N) plus one pass to fill the modes.
  std::vector<DifferenceTerm> energy;
  for (const auto& [kind, weight] : terms_)
    for (DifferenceTerm t : difference_terms(kind)) {
      t.weight *= weight;
      energy.push_back(t);
    }
  const Sides sides = frame_sides(b);
  const int m = b.m, n = b.n;
  const Eigen::VectorXd si = Eigen::VectorXd::LinSpaced(m + 1, 0, 1), sj = Eigen::VectorXd::LinSpaced(n + 1, 0, 1);
  Eigen::MatrixXd A(m + 1, 4), B(n + 1, 4);
  A.col(0) = 1 - si.array();
  A.col(1) = si;
  B.col(2) = 1 - sj.array();
  B.col(3) = sj;
  Eigen::MatrixXd Ui(m + 1, 6), Vj(n + 1, 6);  // the sides: [bottom | top], [left′ | right′]
  Ui << sides.bottom, sides.top;
  Vj.leftCols(3) = sides.left - B.col(2) * sides.left.row(0) - B.col(3) * sides.left.row(n);
  Vj.middleCols(3, 3) = sides.right - B.col(2) * sides.right.row(0) - B.col(3) * sides.right.row(n);
  for (int c = 0; c < 3; ++c) {
    A.col(2) = Ui.col(c);
    A.col(3) = Ui.col(3 + c);
    B.col(0) = Vj.col(c);
    B.col(1) = Vj.col(3 + c);
    for (const DifferenceTerm& t : energy)
      e0_ += t.weight * separable_square_sum(differences(A, t.i_order), differences(B, t.j_order));
  }
  // Factors at the interior points, sine-transformed: [R side (6) | c side (6) | linear blends (2)].
  auto factors = [&](const Eigen::MatrixXd& sides6, const Eigen::MatrixXd& blends, bool i_direction) {
    const Eigen::Index k = sides6.rows() - 2;
    Eigen::MatrixXd F = Eigen::MatrixXd::Zero(k, 14);
    F.leftCols(6) = -normal_interior(sides6, 1);
    for (const DifferenceTerm& t : energy) {
      const int order = i_direction ? t.i_order : t.j_order, other = i_direction ? t.j_order : t.i_order;
      if (other == 0) F.middleCols(6, 6) += t.weight * normal_interior(sides6, order);
    }
    F.rightCols(2) = blends.middleRows(1, k);
    return solvers::sine_transform_1d(F);
  };
  const Eigen::MatrixXd U = factors(Ui, A.leftCols(2), true);   // rows_ × 14
  const Eigen::MatrixXd V = factors(Vj, B.rightCols(2), false); // cols_ × 14

  // ξ = 1 − cos θ = 2 sin²(θ/2) without the cancellation of 1 − cos for the low modes, whose
  // eigenvalues (ξη at α = −1/4, ~1e-11 at N = 1023) carry the whole answer near −1/4.
  auto one_minus_cos = [](int count) {
    Eigen::VectorXd v(count);
    for (int k = 0; k < count; ++k) v(k) = 2 * std::pow(std::sin(M_PI * (k + 1) / (2.0 * (count + 1))), 2);
    return v;
  };
  xi_ = one_minus_cos(rows_);
  eta_ = one_minus_cos(cols_);

  // Per mode: quad = symbol·Σ_xyz R̂², lin = 2·Σ_xyz ĉ·R̂, with the energy's symbol
  // Σ w (2 − 2x)^a (2 − 2y)^b (the eigenvalues of K_a ⊗ K_b on grids vanishing at the frame).
  quad_.resize(Eigen::Index(rows_) * cols_);
  lin_.resize(quad_.size());
  const Eigen::ArrayXd kb = 2 * eta_.array();
  const Eigen::ArrayXd kb_power[3] = {Eigen::ArrayXd::Ones(cols_), kb, kb.square()};  // orders ≤ 2
  Eigen::ArrayXd symbol(cols_);
  for (int p = 0; p < rows_; ++p) {
    const double ka = 2 * xi_(p);
    symbol.setZero();
    for (const DifferenceTerm& t : energy) symbol += t.weight * std::pow(ka, t.i_order) * kb_power[t.j_order];
    const Eigen::Matrix<double, 14, 1> u = U.row(p).transpose();
    const Eigen::Index base = Eigen::Index(p) * cols_;
    mode_row(u.data(), V.data(), cols_, symbol.data(), quad_.data() + base, lin_.data() + base);
  }
}

SpectralAlphaObjective::Value SpectralAlphaObjective::evaluate(double alpha) const {
  // per mode: δ̂ = u·R̂, u = γ/λ, γ = α + 1/4, λ = 1 − 2β(x + y) − 4αxy = λ_C + γd, and
  //   f = E(N_C) + Σ [ quad·u² + lin·u ],  f' = Σ (2·quad·u + lin)·u',
  //   f'' = Σ [ 2·quad·u'² + (2·quad·u + lin)·u'' ],  u' = λ_C/λ², u'' = −2u'd/λ.
  const ModeSums s = mode_sums(alpha, xi_.data(), rows_, eta_.data(), cols_, quad_.data(), lin_.data());
  const double f = e0_ + s.f;
  // f' sums terms of both signs: its rounding error is a few ε of the sum of their sizes
  const double noise = 16 * std::numeric_limits<double>::epsilon() * s.df_abs;
  return {f, s.df, s.d2f, noise, s.smallest >= 1e-14 && std::isfinite(f) && std::isfinite(s.df) && std::isfinite(s.d2f)};
}

SpectralAlphaSearchObjective::SpectralAlphaSearchObjective(const Boundary& boundary, Objective objective)
    : boundary_(boundary), objective_(std::move(objective)), spectral_(boundary, objective_.discrete) {}

SpectralAlphaSearchObjective::Evaluation SpectralAlphaSearchObjective::evaluate(double alpha, bool) {
  ++evaluations_;
  const SpectralAlphaObjective::Value v = spectral_.evaluate(alpha);
  Evaluation e;
  e.parameter = alpha;
  e.value = v.value;
  e.derivative = v.derivative;
  e.second_derivative = v.second_derivative;
  e.derivative_noise = v.derivative_noise;
  e.summary.solver = "spectral";
  e.summary.iterations = 0;
  if (!v.ok) {
    e.summary.status = solvers::SolveStatus::kSingular;
    e.summary.message = "a mode's eigenvalue vanishes at this alpha";
  }
  return e;
}

}  // namespace coons
