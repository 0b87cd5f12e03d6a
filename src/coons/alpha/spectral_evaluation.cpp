// The evaluation of the sine-basis objective (spectral_objective.h) at one α: f, f', f'' and the
// rounding error of f', from the per-mode sums of the discrete terms (spectral_modes.h), the
// Kronecker quadratics (spectral_quadratic.cpp) and the samples of the target.
// Sizes: one pass over the rows × cols modes, a few rows × cols products per quadratic term.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "coons/alpha/spectral_modes.h"
#include "coons/alpha/spectral_objective.h"

namespace coons {

using detail::mode_sums;
using detail::ModeSums;

namespace {

// K̂_a U K̂_b for a term held by mode parity (spectral_objective.h): four products of half size.
template <class Term>
Eigen::MatrixXd kronecker_product_of(const Term& t, const Eigen::MatrixXd& U) {
  Eigen::MatrixXd out(U.rows(), U.cols());
  for (Eigen::Index pr = 0; pr < 2; ++pr)
    for (Eigen::Index pc = 0; pc < 2; ++pc) {
      const auto rows = Eigen::seq(pr, U.rows() - 1, 2);
      const auto cols = Eigen::seq(pc, U.cols() - 1, 2);
      if (rows.size() == 0 || cols.size() == 0) continue;
      const Eigen::MatrixXd block = U(rows, cols);
      out(rows, cols) = t.a[std::size_t(pr)] * block * t.b[std::size_t(pc)];
    }
  return out;
}

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
      const Eigen::MatrixXd KU0 = kronecker_product_of(t, U[c][0]), KU1 = kronecker_product_of(t, U[c][1]);
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

std::array<double, 4> SpectralAlphaObjective::target_sums(const Eigen::MatrixXd (&U)[3][3]) const {
  // The samples S = S_C + P·U·Qᵀ and their derivatives S', S'' in α; per sample p with signed
  // distance d, gradient g and Hessian H: (d²)' = 2d·g·p', (d²)'' = 2(g·p')² + 2d(g·p'' + p'ᵀHp').
  // For a target net S holds the differences to its samples: d² = ‖p‖², (d²)' = 2p·p',
  // (d²)'' = 2(‖p'‖² + p·p'').
  const int k = target_->samples;
  const bool net = target_->kind == Target::Kind::kNet;
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
      if (net) {
        const double pp1 = p0.dot(p1);
        m[0] += p0.squaredNorm();
        m[1] += 2 * pp1;
        m[2] += 2 * (p1.squaredNorm() + p0.dot(p2));
        m[3] += std::abs(2 * pp1);
        continue;
      }
      Eigen::RowVector3d g;
      Eigen::Matrix3d H;
      const double d = target_distance(*target_, p0, &g, &H), gp1 = g.dot(p1);
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
      const auto q = target_sums(U);
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
  // Every term is a sum of squares (weights are positive), but the expansion about the Coons net
  // cancels: a value near 0 comes out as rounding of either sign (the bundled saddle's discrete
  // twist −1.2e-32, E3 of a saddle at 1e50 −6.6e49). A negative one is 0 to rounding.
  v.value = std::max(v.value, 0.0);
  v.ok = v.ok && std::isfinite(v.value) && std::isfinite(v.derivative) && std::isfinite(v.second_derivative);
  return v;
}

}  // namespace coons
