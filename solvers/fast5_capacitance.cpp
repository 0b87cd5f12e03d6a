#include "fast5_capacitance.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "fast5_modes.h"
#include "vector_clones.h"

namespace coons::solvers::fast5_detail {

namespace {

// Σ_p a[p]·b[p] in eight interleaved partial sums (so that the AVX2 clone adds whole vectors; the
// order of the sums is the same in either clone, and so are the bits).
COONS_VECTOR_CLONES double dot8(const double* __restrict a, const double* __restrict b, Eigen::Index n) {
  std::array<double, 8> acc{};
  Eigen::Index p = 0;
  for (; p + 8 <= n; p += 8)
    for (std::size_t l = 0; l < 8; ++l) acc[l] += a[p + Eigen::Index(l)] * b[p + Eigen::Index(l)];
  double sum = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
  for (; p < n; ++p) sum += a[p] * b[p];
  return sum;
}

// The four dots a_i·b_j (i, j < 2), each summed exactly as dot8 sums it (lane l of an accumulator
// is dot8's partial sum l; so the same bits): a and b are each loaded once for two dots, and the
// chains of additions hide each other's latency (dot8 alone waits on two). One AVX-512 register
// per dot in that clone: the G products are bound by arithmetic (0.3 ms of a 16 ms solve at
// N = 1023 against the AVX2 clone).
COONS_WIDE_CLONES std::array<double, 4> dot8_2x2(const double* a0, const double* a1, const double* b0, const double* b1,
                                                 Eigen::Index n) {
  using detail::Lanes8;  // vector_clones.h
  Lanes8 s00{}, s01{}, s10{}, s11{};
  Eigen::Index p = 0;
  for (; p + 8 <= n; p += 8) {
    Lanes8 x0, x1, y0, y1;
    std::memcpy(&x0, a0 + p, sizeof x0);
    std::memcpy(&x1, a1 + p, sizeof x1);
    std::memcpy(&y0, b0 + p, sizeof y0);
    std::memcpy(&y1, b1 + p, sizeof y1);
    s00 += x0 * y0;
    s01 += x0 * y1;
    s10 += x1 * y0;
    s11 += x1 * y1;
  }
  const auto total = [](const Lanes8& l) { return ((l[0] + l[1]) + (l[2] + l[3])) + ((l[4] + l[5]) + (l[6] + l[7])); };
  std::array<double, 4> sums{total(s00), total(s01), total(s10), total(s11)};
  for (; p < n; ++p) {
    sums[0] += a0[p] * b0[p];
    sums[1] += a0[p] * b1[p];
    sums[2] += a1[p] * b0[p];
    sums[3] += a1[p] * b1[p];
  }
  return sums;
}

// y −= alpha·x.
COONS_VECTOR_CLONES void subtract_scaled(double alpha, const double* __restrict x, double* __restrict y,
                                         Eigen::Index n) {
  for (Eigen::Index p = 0; p < n; ++p) y[p] -= alpha * x[p];
}

// y −= alpha0·x0, then y −= alpha1·x1: two subtract_scaled in one pass over y (the same bits).
COONS_WIDE_CLONES void subtract_scaled2(double alpha0, const double* __restrict x0, double alpha1,
                                        const double* __restrict x1, double* __restrict y, Eigen::Index n) {
  for (Eigen::Index p = 0; p < n; ++p) y[p] = (y[p] - alpha0 * x0[p]) - alpha1 * x1[p];
}

// out[m] = 1/λ(μ_m, ν) = 1/(a μ_m² ν² + b (μ_m + ν)²), a loop the AVX2 clone divides four at a time.
COONS_VECTOR_CLONES void inverse_eigenvalues(double a, double b, const double* __restrict mu, double nu,
                                             double* __restrict out, Eigen::Index n) {
  for (Eigen::Index m = 0; m < n; ++m) {
    const double s = mu[m] + nu;
    out[m] = 1 / (a * mu[m] * mu[m] * nu * nu + b * s * s);
  }
}

// The cross approximation of diag^{−1/2}·G stops at this relative size of its last term (the
// preconditioned solve is then about 1e−8 off, and one correction by its residual about 1e−16);
// its rank is capped (27–28 at 1e−8 on N = 1023) so that a block's set-up stays O(#modes·rank²).
constexpr double kPreconditionerTolerance = 1e-8;
constexpr int kPreconditionerRank = 64;
// solve: the one correction after P⁻¹ rhs is taken when the squared relative residual of P⁻¹ rhs
// is below this share of the tolerance (the correction leaves about that square).
constexpr double kCorrectionShare = 0.1;

// One column of a block, with inv = 1/λ(·, q) over the block's modes: diag += t_q²·inv,
// g = c·σ⊙inv, k0 += ts0·inv, k1 += ts1·inv (the AVX2 clone four modes at a time; no sums, so the
// same bits in either clone).
COONS_VECTOR_CLONES void fill_column(const double* __restrict inv, const double* __restrict sigma, double tt, double c,
                                     double ts0, double ts1, double* __restrict diag, double* __restrict g,
                                     double* __restrict k0, double* __restrict k1, Eigen::Index n) {
  for (Eigen::Index m = 0; m < n; ++m) {
    diag[m] += tt * inv[m];
    g[m] = c * sigma[m] * inv[m];
    k0[m] += ts0 * inv[m];
    k1[m] += ts1 * inv[m];
  }
}

}  // namespace

// out(k, c) = G.col(k)·V.col(c) for k in [k0, k0 + 2) ∩ [0, #G) and every c, two by two.
void dots_of_columns(const Eigen::MatrixXd& G, Eigen::Index k0, const Eigen::MatrixXd& V, Eigen::MatrixXd& out) {
  const Eigen::Index n = G.rows(), m = V.cols();
  if (k0 + 1 >= G.cols()) {
    for (Eigen::Index c = 0; c < m; ++c) out(k0, c) = dot8(G.col(k0).data(), V.col(c).data(), n);
    return;
  }
  const double *g0 = G.col(k0).data(), *g1 = G.col(k0 + 1).data();
  Eigen::Index c = 0;
  for (; c + 2 <= m; c += 2) {
    const std::array<double, 4> d = dot8_2x2(g0, g1, V.col(c).data(), V.col(c + 1).data(), n);
    out(k0, c) = d[0];
    out(k0, c + 1) = d[1];
    out(k0 + 1, c) = d[2];
    out(k0 + 1, c + 1) = d[3];
  }
  for (; c < m; ++c) {
    out(k0, c) = dot8(g0, V.col(c).data(), n);
    out(k0 + 1, c) = dot8(g1, V.col(c).data(), n);
  }
}

void subtract_columns(const Eigen::MatrixXd& G, Eigen::Index k0, const Eigen::MatrixXd& coef, bool negate,
                      Eigen::MatrixXd& out) {
  // negated, not multiplied by −1 (the same for numbers; a NaN keeps the sign it had before)
  const auto alpha = [&](Eigen::Index k, Eigen::Index c) { return negate ? -coef(k, c) : coef(k, c); };
  const Eigen::Index n = G.rows();
  for (Eigen::Index c = 0; c < out.cols(); ++c) {
    if (k0 + 1 < G.cols())
      subtract_scaled2(alpha(k0, c), G.col(k0).data(), alpha(k0 + 1, c), G.col(k0 + 1).data(), out.col(c).data(), n);
    else
      subtract_scaled(alpha(k0, c), G.col(k0).data(), out.col(c).data(), n);
  }
}

void CapacitanceBlock::build_preconditioner(const CrossApproximation& cross) {
  const Eigen::Index n = diag.size();
  W.resize(n, 0);
  S_factor.resize(0, 0);
  if (n == 0) return;
  // s G Gᵀ s ≈ U (VᵀV) Uᵀ = (U L)(U L)ᵀ with VᵀV = L Lᵀ
  const Eigen::Index k = cross.U.cols();
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(k, k);
  gram.selfadjointView<Eigen::Lower>().rankUpdate(cross.V.transpose());
  const Eigen::LLT<Eigen::MatrixXd> gram_factor(gram);
  if (gram_factor.info() != Eigen::Success) return;
  Eigen::MatrixXd w(n, k + 1);
  w.col(0) = std::sqrt(std::max(kappa, 0.0)) * scale.cwiseProduct(u);
  // (k = 0: a block without columns q, cols = 1; Eigen's product of inner size 0 divides by zero)
  if (k > 0) w.rightCols(k).noalias() = cross.U * gram_factor.matrixL();
  Eigen::MatrixXd s = Eigen::MatrixXd::Identity(k + 1, k + 1);
  s.selfadjointView<Eigen::Lower>().rankUpdate(w.transpose(), -1.0);
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) return;
  W = std::move(w);
  S_factor = llt.matrixL();
}

void CapacitanceBlock::precondition(const Eigen::MatrixXd& R, Eigen::MatrixXd& Z) const {
  Z = scale.asDiagonal() * R;
  if (W.cols() == 0) {
    Z = scale.asDiagonal() * Z;
    return;
  }
  Eigen::MatrixXd t = W.transpose() * Z;  // (I + W S⁻¹ Wᵀ), S = L Lᵀ
  S_factor.triangularView<Eigen::Lower>().solveInPlace(t);
  S_factor.transpose().triangularView<Eigen::Upper>().solveInPlace(t);
  Z.noalias() += W * t;
  Z = scale.asDiagonal() * Z;
}

// out = Cap·V, with G Gᵀ V = Σ_k g_k (g_kᵀ V) over the columns g_k of G: each column is read
// once, for all right-hand sides, and used twice while it is in the L1 cache (hand-written:
// Eigen's product would pack G into a copy on every call, and its kernels are the build's SSE2
// ones, see dot8).
void CapacitanceBlock::apply(const Eigen::MatrixXd& V, Eigen::MatrixXd& out) const {
  out.noalias() = diag.asDiagonal() * V;
  out.noalias() -= (kappa * u) * (u.transpose() * V);
  Eigen::MatrixXd dots(G.cols(), V.cols());
  for (Eigen::Index k = 0; k < G.cols(); k += 2) {  // two columns of G at a time, both in the L1 cache
    dots_of_columns(G, k, V, dots);
    subtract_columns(G, k, dots, false, out);
  }
}

// V ← H⁻¹ V (rows of V are this block's modes).
void CapacitanceBlock::apply_h_inverse(Eigen::MatrixXd& V) const {
  const Eigen::RowVectorXd uv = u.transpose() * V;
  V = h_inv.asDiagonal() * V;
  V.noalias() -= (kappa * u) * uv;
}

// P⁻¹ rhs and one correction by its residual when that suffices, otherwise preconditioned conjugate
// gradients from there, one column per right-hand side (each with its own step lengths; a
// converged column is frozen); returns the products with Cap.
int CapacitanceBlock::solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& X, double tolerance) const {
  const Eigen::Index n = rhs.rows(), m = rhs.cols();
  X.setZero(n, m);
  if (n == 0 || m == 0) return 0;
  const Eigen::ArrayXd norms = rhs.colwise().norm().transpose().array();
  const Eigen::ArrayXd target = tolerance * norms;
  Eigen::MatrixXd R = rhs, Z, P, AP;
  int applied = 0;
  if (W.cols() > 0) {
    // P⁻¹ rhs is within about the preconditioner's accuracy ρ (relative residual, about 1e−8) of
    // the solution, and one correction by the residual brings that to about ρ²: taken, with one
    // pass over G, when ρ² is below the tolerance; otherwise CG goes on from there.
    precondition(rhs, X);
    apply(X, AP);
    R -= AP;
    applied = 1;
    bool corrected = true;
    for (Eigen::Index c = 0; c < m; ++c) {
      const double rho = norms[c] > 0 ? R.col(c).norm() / norms[c] : 0.0;
      corrected = corrected && rho * rho <= kCorrectionShare * tolerance;
    }
    if (corrected) {
      precondition(R, Z);
      X += Z;
      return applied;
    }
  }
  precondition(R, Z);
  P = Z;
  Eigen::ArrayXd rz = (R.cwiseProduct(Z)).colwise().sum().transpose().array();
  std::vector<bool> active(static_cast<std::size_t>(m), false);
  for (Eigen::Index c = 0; c < m; ++c) active[std::size_t(c)] = target[c] > 0 && R.col(c).norm() > target[c];
  const int limit = int(2 * n + 50);
  for (int k = 1; k <= limit; ++k) {
    if (std::none_of(active.begin(), active.end(), [](bool a) { return a; })) return applied + k - 1;
    apply(P, AP);
    bool any = false;
    for (Eigen::Index c = 0; c < m; ++c) {
      if (!active[std::size_t(c)]) continue;
      const double step = rz[c] / P.col(c).dot(AP.col(c));
      X.col(c) += step * P.col(c);
      R.col(c) -= step * AP.col(c);
      if (R.col(c).norm() <= target[c]) {
        active[std::size_t(c)] = false;
        R.col(c).setZero();
        P.col(c).setZero();
        continue;
      }
      any = true;
    }
    if (!any) return applied + k;
    precondition(R, Z);
    for (Eigen::Index c = 0; c < m; ++c) {
      if (!active[std::size_t(c)]) continue;
      const double rz_next = R.col(c).dot(Z.col(c));
      P.col(c) = Z.col(c) + (rz_next / rz[c]) * P.col(c);
      rz[c] = rz_next;
    }
  }
  return applied + limit;
}

BlockInputs block_inputs(double a, double b, const Eigen::VectorXd& mu, const Eigen::VectorXd& nu,
                         const Eigen::VectorXd& t) {
  BlockInputs in{a, b, mu, nu, t, std::sqrt(2.0) * first_sine_column(int(mu.size())), {}, {}};
  // t_q·s_j(q) for the grid columns j = 0, 1 (s_j the orthonormal sine vector of column j)
  const int cols = int(nu.size());
  const double scale_j = std::sqrt(2.0 / (cols + 1));
  in.ts0.resize(cols);
  in.ts1.resize(cols);
  for (int q = 0; q < cols; ++q) {
    in.ts0[q] = t[q] * scale_j * std::sin(M_PI * (q + 1) / (cols + 1));
    in.ts1[q] = t[q] * scale_j * std::sin(M_PI * 2 * (q + 1) / (cols + 1));
  }
  return in;
}

CapacitanceBlock capacitance_block(const BlockInputs& in, int index) {
  const double a = in.a, b = in.b;
  const Eigen::VectorXd &mu = in.mu, &nu = in.nu, &t = in.t, &sigma = in.sigma, &ts0 = in.ts0, &ts1 = in.ts1;
  const int rows = int(mu.size()), cols = int(nu.size());
  const int qpar = index / 2, ppar = index % 2;
  CapacitanceBlock blk;
  std::vector<int>& qs = blk.columns;
  qs.clear();
  for (int q = qpar; q < cols; q += 2) qs.push_back(q);
  blk.modes.clear();
  for (int p = ppar; p < rows; p += 2) blk.modes.push_back(p);
  const auto n = Eigen::Index(blk.modes.size());
  blk.diag.resize(n);
  blk.h_inv.resize(n);
  blk.u.resize(n);
  blk.G.resize(n, Eigen::Index(qs.size()));
  blk.c.resize(Eigen::Index(qs.size()));
  blk.K.setZero(n, 2);
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
  Eigen::VectorXd inv_lambda(n), mu_b(n), sigma_b(n);  // μ_p and σ_p of the block's modes, contiguous
  for (Eigen::Index m = 0; m < n; ++m) {
    mu_b[m] = mu[blk.modes[std::size_t(m)]];
    sigma_b[m] = sigma[blk.modes[std::size_t(m)]];
  }
  blk.sigma = sigma_b;
  const Eigen::VectorXd sigma2 = sigma_b.cwiseProduct(sigma_b);
  for (std::size_t k = 0; k < qs.size(); ++k) {
    const int q = qs[k];
    const double alpha = a * nu[q] * nu[q] + b;  // the weight of E_i in M_q
    inverse_eigenvalues(a, b, mu_b.data(), nu[q], inv_lambda.data(), n);
    const double gamma = dot8(sigma2.data(), inv_lambda.data(), n);  // σᵀΛ_q⁻¹σ on the block
    const double c = std::sqrt(t[q] * t[q] * alpha / (1 + alpha * gamma));
    blk.c[Eigen::Index(k)] = c;
    fill_column(inv_lambda.data(), sigma_b.data(), t[q] * t[q], c, ts0[q], ts1[q], blk.diag.data(),
                blk.G.col(Eigen::Index(k)).data(), blk.K.col(0).data(), blk.K.col(1).data(), n);
  }
  // the cross approximation of diag^{−1/2}·G from its entries' closed form (a row of the stored G
  // would be read across #modes cache lines and pages)
  blk.scale = blk.diag.cwiseSqrt().cwiseInverse();
  Eigen::VectorXd nu_b(Eigen::Index(qs.size()));
  for (std::size_t k = 0; k < qs.size(); ++k) nu_b[Eigen::Index(k)] = nu[qs[k]];
  const auto row_of = [&](Eigen::Index m, Eigen::VectorXd& out) {  // 1/λ symmetric in (μ, ν)
    inverse_eigenvalues(a, b, nu_b.data(), mu_b[m], out.data(), out.size());
    out = (blk.scale[m] * sigma_b[m]) * blk.c.cwiseProduct(out);
  };
  const auto col_of = [&](Eigen::Index k, Eigen::VectorXd& out) {
    inverse_eigenvalues(a, b, mu_b.data(), nu_b[k], out.data(), out.size());
    out = blk.c[k] * blk.scale.cwiseProduct(sigma_b).cwiseProduct(out);
  };
  blk.build_preconditioner(
      cross_approximation(n, Eigen::Index(qs.size()), row_of, col_of, kPreconditionerTolerance, kPreconditionerRank));
  return blk;
}

std::array<CapacitanceBlock, 4> capacitance_blocks(double a, double b, const Eigen::VectorXd& mu,
                                                   const Eigen::VectorXd& nu, const Eigen::VectorXd& t, int threads) {
  const BlockInputs in = block_inputs(a, b, mu, nu, t);
  std::array<CapacitanceBlock, 4> blocks;
  [[maybe_unused]] const int nt = threads;
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static, 1)
#endif
  for (int index = 0; index < 4; ++index) blocks[std::size_t(index)] = capacitance_block(in, index);  // one thread each
  return blocks;
}

}  // namespace coons::solvers::fast5_detail
