#include "spectral_objective.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
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

// The Bernstein basis of a degree at the k samples s/(k − 1) of sample_surface (#k by degree+1).
Eigen::MatrixXd basis_at_samples(int degree, int k) {
  Eigen::MatrixXd B(k, degree + 1);
  for (int s = 0; s < k; ++s) B.row(s) = bernstein_basis(degree, double(s) / (k - 1)).transpose();
  return B;
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

bool SpectralAlphaObjective::supports(const Objective& o) {
  const bool target = o.target_weight > 0;
  return (!o.discrete.empty() || !o.energy.empty() || target) && (!target || o.target);
}

SpectralAlphaObjective::SpectralAlphaObjective(const Boundary& b, const Objective& objective)
    : rows_(b.m - 1), cols_(b.n - 1) {
  assert(rows_ >= 1 && cols_ >= 1 && supports(objective));
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
  for (const auto& [kind, weight] : objective.discrete)
    for (DifferenceTerm t : difference_terms(kind)) {
      t.weight *= weight;
      energy.push_back(t);
    }
  const Sides sides = frame_sides(b);
  const int m = b.m, n = b.n;
  const Eigen::VectorXd si = Eigen::VectorXd::LinSpaced(m + 1, 0, 1), sj = Eigen::VectorXd::LinSpaced(n + 1, 0, 1);
  Eigen::MatrixXd A[3], B[3];  // N_C = A[c]·B[c]ᵀ per coordinate
  Eigen::MatrixXd Ui(m + 1, 6), Vj(n + 1, 6);  // the sides: [bottom | top], [left′ | right′]
  Ui << sides.bottom, sides.top;
  Vj.leftCols(3) = sides.left - (1 - sj.array()).matrix() * sides.left.row(0) - sj * sides.left.row(n);
  Vj.middleCols(3, 3) = sides.right - (1 - sj.array()).matrix() * sides.right.row(0) - sj * sides.right.row(n);
  for (int c = 0; c < 3; ++c) {
    A[c].resize(m + 1, 4);
    B[c].resize(n + 1, 4);
    A[c] << 1 - si.array(), si, Ui.col(c), Ui.col(3 + c);
    B[c] << Vj.col(c), Vj.col(3 + c), 1 - sj.array(), sj;
    for (const DifferenceTerm& t : energy)
      e0_ += t.weight * separable_square_sum(differences(A[c], t.i_order), differences(B[c], t.j_order));
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
  const Eigen::MatrixXd U = factors(Ui, A[0].leftCols(2), true);   // rows_ × 14
  const Eigen::MatrixXd V = factors(Vj, B[0].rightCols(2), false); // cols_ × 14

  // ξ = 1 − cos θ = 2 sin²(θ/2) without the cancellation of 1 − cos for the low modes, whose
  // eigenvalues (ξη at α = −1/4, ~1e-11 at N = 1023) carry the whole answer near −1/4.
  auto one_minus_cos = [](int count) {
    Eigen::VectorXd v(count);
    for (int k = 0; k < count; ++k) v(k) = 2 * std::pow(std::sin(M_PI * (k + 1) / (2.0 * (count + 1))), 2);
    return v;
  };
  xi_ = one_minus_cos(rows_);
  eta_ = one_minus_cos(cols_);

  if (!objective.energy.empty() || objective.target_weight > 0) {
    // R̂ made dense from its four separable parts (columns of U and V as laid out above)
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd Ur(rows_, 4), Vr(cols_, 4);
      Ur << U.col(c), U.col(3 + c), U.col(12), U.col(13);
      Vr << V.col(12), V.col(13), V.col(c), V.col(3 + c);
      r_hat_[c] = Ur * Vr.transpose();
    }
    const ControlNet coons = discrete_coons_net(b);
    if (!objective.energy.empty()) {
      exact_ = exact_energies(coons, objective.energy, A, B);
    }
    if (objective.target_weight > 0) {
      target_weight_ = objective.target_weight;
      if (objective.target->kind == Target::Kind::kNet) {
        target_ = mean_square_distance(coons, objective.target->net, objective.target->samples);
      } else {
        analytic_ = objective.target;
        const int k = analytic_->samples;
        const Eigen::MatrixXd Bu = basis_at_samples(b.m, k), Bv = basis_at_samples(b.n, k);
        p_ = solvers::sine_transform_1d(Bu.middleCols(1, rows_).transpose()).transpose();
        q_ = solvers::sine_transform_1d(Bv.middleCols(1, cols_).transpose()).transpose();
        for (int c = 0; c < 3; ++c) coons_samples_[c] = Bu * coordinate_grid(coons, c) * Bv.transpose();
      }
    }
  }
  if (energy.empty()) return;  // no discrete terms

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

namespace {

// K_a = D_aᵀ G D_a ((k+1) × (k+1)): ∫(∂^a f)² = fᵀ K_a f for f in the Bernstein basis of degree k,
// D_a the derivative's coefficients k!/(k−a)!·Δ^a and G the Gram matrix of degree k − a.
Eigen::MatrixXd derivative_gram(int k, int a) {
  if (a > k) return Eigen::MatrixXd::Zero(k + 1, k + 1);
  Eigen::MatrixXd D = Eigen::MatrixXd::Identity(k + 1, k + 1);
  for (int r = 0; r < a; ++r) D = ((k - r) * (D.bottomRows(D.rows() - 1) - D.topRows(D.rows() - 1))).eval();
  return D.transpose() * bernstein_gram(k - a) * D;
}

// S_r·G·S_c: the 2-D sine transform of a rows × cols grid held as a matrix.
Eigen::MatrixXd sine_2d(const Eigen::MatrixXd& G) {
  return solvers::sine_transform_1d(solvers::sine_transform_1d(G).transpose()).transpose();
}

// S·K·S of the interior block of K (S the orthonormal DST-I, its own transpose).
Eigen::MatrixXd sine_both_sides(const Eigen::MatrixXd& K) {
  const Eigen::Index k = K.rows() - 2;
  return sine_2d(K.block(1, 1, k, k));
}

}  // namespace

SpectralAlphaObjective::Quadratic SpectralAlphaObjective::exact_energies(const ControlNet& coons,
                                                                        const std::vector<EnergyTerm>& exact,
                                                                        const Eigen::MatrixXd (&A)[3],
                                                                        const Eigen::MatrixXd (&B)[3]) const {
  // Σ w·tr(Nᵀ K_a N K_b) per coordinate: ĉ as the outer product of the transformed K_a A and K_b B
  // at the interior, and E(N_C) from the Coons net itself: the factors' 4×4 Gram matrices would
  // lose ε·‖K_a A‖‖K_b B‖ to cancellation (1e-14 where E(N_C) = 0, as for the twist of a bilinear
  // boundary), and this costs no more than one evaluation.
  const int m = rows_ + 1, n = cols_ + 1;
  Quadratic q;
  q.constant = combined_energy(coons, exact);
  for (auto& c_hat : q.c_hat) c_hat = Eigen::MatrixXd::Zero(rows_, cols_);
  for (const EnergyTerm& t : exact) {
    const Eigen::MatrixXd Ka = derivative_gram(m, t.a), Kb = derivative_gram(n, t.b);
    for (int c = 0; c < 3; ++c) {
      const Eigen::MatrixXd KA = Ka * A[c], KB = Kb * B[c];
      q.c_hat[c] += t.weight * solvers::sine_transform_1d(KA.middleRows(1, rows_)) *
                    solvers::sine_transform_1d(KB.middleRows(1, cols_)).transpose();
      q.c_scale += std::abs(t.weight) * KA.norm() * KB.norm();
    }
    q.terms.push_back({sine_both_sides(Ka), sine_both_sides(Kb), t.weight});
  }
  return q;
}

SpectralAlphaObjective::Quadratic SpectralAlphaObjective::mean_square_distance(const ControlNet& coons,
                                                                              const ControlNet& target,
                                                                              int samples) const {
  // (1/k²) Σ_xyz ‖B_u N B_vᵀ − T‖², T the target sampled at the same (u, v) (objective.cpp).
  const int m = rows_ + 1, n = cols_ + 1, k = samples;
  const Eigen::MatrixXd Bu = basis_at_samples(m, k), Bv = basis_at_samples(n, k);
  const Eigen::MatrixX3d T = sample_surface(target, k, k);
  Quadratic q;
  for (int c = 0; c < 3; ++c) {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::MatrixXd Tc = Eigen::Map<const RowMajor>(T.col(c).data(), k, k);
    const Eigen::MatrixXd D = (Bu * coordinate_grid(coons, c) * Bv.transpose() - Tc) / k;  // q = ‖D‖²
    q.constant += D.squaredNorm();
    const Eigen::MatrixXd G = Bu.transpose() * D * Bv / k;  // half the gradient
    q.c_hat[c] = sine_2d(G.block(1, 1, rows_, cols_));
    q.c_scale += Bu.norm() * Bv.norm() / k * (D.norm() + Tc.norm() / k);
  }
  q.terms.push_back({sine_both_sides(Bu.transpose() * Bu), sine_both_sides(Bv.transpose() * Bv / (double(k) * k)), 1.0});
  return q;
}

namespace {

// q, q', q'' and the rounding error of q' of a quadratic at U[c][r] = u^(r)∘R̂_c (r = 0, 1, 2):
//   q = constant + 2⟨ĉ, U⟩ + Σ w⟨U, K̂_a U K̂_b⟩,  q' = 2⟨ĉ, U'⟩ + 2Σ w⟨U', K̂_a U K̂_b⟩,
//   q'' = 2⟨ĉ, U''⟩ + 2Σ w(⟨U'', K̂_a U K̂_b⟩ + ⟨U', K̂_a U' K̂_b⟩).
template <class Quadratic>
std::array<double, 4> quadratic_sums(const Quadratic& q, const Eigen::MatrixXd (&U)[3][3]) {
  std::array<double, 4> r = {q.constant, 0, 0, 0};
  for (int c = 0; c < 3; ++c) {
    r[0] += 2 * q.c_hat[c].cwiseProduct(U[c][0]).sum();
    r[1] += 2 * q.c_hat[c].cwiseProduct(U[c][1]).sum();
    r[2] += 2 * q.c_hat[c].cwiseProduct(U[c][2]).sum();
    r[3] += 2 * (q.c_hat[c].norm() + q.c_scale) * U[c][1].norm();
    for (const auto& t : q.terms) {
      const Eigen::MatrixXd KU0 = t.a * U[c][0] * t.b, KU1 = t.a * U[c][1] * t.b;
      r[0] += t.weight * U[c][0].cwiseProduct(KU0).sum();
      r[1] += 2 * t.weight * U[c][1].cwiseProduct(KU0).sum();
      r[2] += 2 * t.weight * (U[c][2].cwiseProduct(KU0).sum() + U[c][1].cwiseProduct(KU1).sum());
      r[3] += 2 * std::abs(t.weight) * U[c][1].norm() * KU0.norm();
    }
  }
  r[3] *= 16 * std::numeric_limits<double>::epsilon();
  return r;
}

}  // namespace

std::array<double, 4> SpectralAlphaObjective::analytic_sums(const Eigen::MatrixXd (&U)[3][3]) const {
  // The samples S = S_C + P·U·Qᵀ and their derivatives S', S'' in α; per sample p with signed
  // distance d, gradient g and Hessian H: (d²)' = 2d·g·p', (d²)'' = 2(g·p')² + 2d(g·p'' + p'ᵀHp').
  const int k = analytic_->samples;
  Eigen::MatrixXd S[3][3];
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      S[c][r] = p_ * U[c][r] * q_.transpose();
      if (r == 0) S[c][r] += coons_samples_[c];
    }
  std::array<double, 4> m = {0, 0, 0, 0};
  for (int s = 0; s < k; ++s)
    for (int t = 0; t < k; ++t) {
      const Eigen::RowVector3d p0(S[0][0](s, t), S[1][0](s, t), S[2][0](s, t)),
          p1(S[0][1](s, t), S[1][1](s, t), S[2][1](s, t)), p2(S[0][2](s, t), S[1][2](s, t), S[2][2](s, t));
      Eigen::RowVector3d g;
      Eigen::Matrix3d H;
      const double d = target_distance(*analytic_, p0, &g, &H), gp1 = g.dot(p1);
      m[0] += d * d;
      m[1] += 2 * d * gp1;
      m[2] += 2 * (gp1 * gp1 + d * (g.dot(p2) + p1 * H * p1.transpose()));
      m[3] += std::abs(2 * d * gp1);
    }
  const double samples = double(k) * k;
  return {m[0] / samples, m[1] / samples, m[2] / samples, 16 * std::numeric_limits<double>::epsilon() * m[3] / samples};
}

SpectralAlphaObjective::Value SpectralAlphaObjective::evaluate(double alpha) const {
  // per mode: δ̂ = u·R̂, u = γ/λ, γ = α + 1/4, λ = 1 − 2β(x + y) − 4αxy = λ_C + γd, and
  //   f = E(N_C) + Σ [ quad·u² + lin·u ],  f' = Σ (2·quad·u + lin)·u',
  //   f'' = Σ [ 2·quad·u'² + (2·quad·u + lin)·u'' ],  u' = λ_C/λ², u'' = −2u'd/λ.
  Value v;
  v.value = e0_;
  v.ok = true;
  if (quad_.size() > 0) {
    const ModeSums s = mode_sums(alpha, xi_.data(), rows_, eta_.data(), cols_, quad_.data(), lin_.data());
    v.value += s.f;
    v.derivative += s.df;
    v.second_derivative += s.d2f;
    // f' sums terms of both signs: its rounding error is a few ε of the sum of their sizes
    v.derivative_noise = 16 * std::numeric_limits<double>::epsilon() * s.df_abs;
    v.ok = s.smallest >= 1e-14;
  }
  if (!exact_.terms.empty() || target_weight_ > 0) {
    // U = u∘R̂ per coordinate, with u, u', u'' per mode as in mode_sums
    const double gamma = alpha + 0.25;
    const Eigen::ArrayXXd lc = (xi_ * eta_.transpose()).array();
    const Eigen::ArrayXXd d =
        2 * (xi_.replicate(1, cols_).array() + eta_.transpose().replicate(rows_, 1).array() - 2 * lc);
    const Eigen::ArrayXXd lambda = lc + gamma * d, il = lambda.inverse();
    const Eigen::ArrayXXd u[3] = {gamma * il, lc * il.square(), -2 * lc * il.square() * d * il};
    Eigen::MatrixXd U[3][3];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) U[c][r] = (u[r] * r_hat_[c].array()).matrix();
    if (!exact_.terms.empty()) {
      const auto q = quadratic_sums(exact_, U);
      v.value += q[0];
      v.derivative += q[1];
      v.second_derivative += q[2];
      v.derivative_noise += q[3];
    }
    if (target_weight_ > 0) {  // w·√q, q the mean square distance and its derivatives
      const auto q = analytic_ ? analytic_sums(U) : quadratic_sums(target_, U);
      const double rms = std::sqrt(std::max(q[0], 0.0)), w = target_weight_;
      v.value += w * rms;
      if (rms > 0) {
        v.derivative += w * q[1] / (2 * rms);
        v.second_derivative += w * (q[2] / (2 * rms) - q[1] * q[1] / (4 * rms * rms * rms));
        v.derivative_noise += w * q[3] / (2 * rms);
      }
    }
    v.ok = v.ok && lambda.abs().minCoeff() >= 1e-14;
  }
  v.ok = v.ok && std::isfinite(v.value) && std::isfinite(v.derivative) && std::isfinite(v.second_derivative);
  return v;
}

SpectralAlphaSearchObjective::SpectralAlphaSearchObjective(const Boundary& boundary, Objective objective)
    : boundary_(boundary), objective_(std::move(objective)), spectral_(boundary, objective_) {}

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
