#include "continuum_limit.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>

#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/net/quadrature.h"

namespace coons {

namespace {

constexpr int kMaxOrder = 3;  //!< derivatives up to third order (E3)

//! out[r](k − 2, q) = φ_k^(r)(u_q), k = 2..N, r = 0..3, φ_k = (P_k − P_{k−2})(2u − 1)/√(2(2k − 1)).
std::vector<Eigen::MatrixXd> bubbles(int N, const Eigen::VectorXd& u) {
  const auto q = u.size();
  // P[r](j, q): the r-th x-derivative of the Legendre polynomial P_j at x = 2u − 1, j = 0..N
  std::vector<Eigen::MatrixXd> P(kMaxOrder + 1, Eigen::MatrixXd::Zero(N + 1, q));
  for (Eigen::Index s = 0; s < q; ++s) {
    const double x = 2 * u(s) - 1;
    P[0](0, s) = 1;
    if (N >= 1) P[0](1, s) = x;
    for (int j = 1; j < N; ++j) P[0](j + 1, s) = ((2 * j + 1) * x * P[0](j, s) - j * P[0](j - 1, s)) / (j + 1);
    for (int r = 1; r <= kMaxOrder; ++r) {
      if (N >= 1) P[r](1, s) = r == 1 ? 1 : 0;
      for (int j = 1; j < N; ++j) P[r](j + 1, s) = P[r](j - 1, s) + (2 * j + 1) * P[r - 1](j, s);
    }
  }
  std::vector<Eigen::MatrixXd> out(kMaxOrder + 1, Eigen::MatrixXd(std::max(N - 1, 0), q));
  for (int r = 0; r <= kMaxOrder; ++r)
    for (int k = 2; k <= N; ++k)
      out[size_t(r)].row(k - 2) =
          std::pow(2.0, r) * (P[size_t(r)].row(k) - P[size_t(r)].row(k - 2)) / std::sqrt(2.0 * (2 * k - 1));
  return out;
}

//! Rows q of B_i^k(u_q): #nodes by k+1.
Eigen::MatrixXd bernstein_at(int k, const Eigen::VectorXd& u) {
  Eigen::MatrixXd B(u.size(), k + 1);
  for (Eigen::Index s = 0; s < u.size(); ++s) B.row(s) = bernstein_basis(k, u(s)).transpose();
  return B;
}

//! Σ_ij w_i w_j D_ij²
double weighted_square(const Eigen::MatrixXd& D, const Eigen::VectorXd& w) { return w.dot(D.cwiseAbs2() * w); }

}  // namespace

ContinuumProblem::ContinuumProblem(const Boundary& boundary)
    : degree_(boundary.m), coons_(discrete_coons_net(boundary)) {
  const int N = degree_;
  Eigen::RowVector3d lo = coons_.at(0, 0), hi = lo;
  for (int i = 0; i <= coons_.m; ++i)
    for (int j = 0; j <= coons_.n; ++j) {
      lo = lo.cwiseMin(coons_.at(i, j));
      hi = hi.cwiseMax(coons_.at(i, j));
    }
  scale_ = (hi - lo).squaredNorm();
  const QuadratureRule rule = gauss_legendre(N + 2);
  nodes_ = rule.nodes;
  weights_ = rule.weights;
  phi_ = bubbles(N, nodes_);
  const Eigen::MatrixXd W = weights_.asDiagonal();
  base_.assign(3, std::vector<Eigen::MatrixXd>((kMaxOrder + 1) * (kMaxOrder + 1)));
  for (int a = 0; a <= kMaxOrder; ++a)
    for (int b = 0; b <= kMaxOrder; ++b) {
      const ControlNet d = derivative_net(coons_, a, b);
      const Eigen::MatrixXd Bu = bernstein_at(d.m, nodes_), Bv = bernstein_at(d.n, nodes_);
      for (int c = 0; c < 3; ++c)
        base_[size_t(c)][size_t(a) * 4 + size_t(b)] = Bu * coordinate_grid(d, c) * Bv.transpose();
    }
  if (N < 2) return;
  const Eigen::MatrixXd M = phi_[0] * W * phi_[0].transpose(), K = phi_[1] * W * phi_[1].transpose();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  V_ = eig.eigenvectors();
  lambda_ = eig.eigenvalues();
  for (int c = 0; c < 3; ++c) {
    const auto& P = base_[size_t(c)];
    const Eigen::MatrixXd Rt = phi_[1] * W * P[1 * 4 + 1] * W * phi_[1].transpose();
    const Eigen::MatrixXd Rd =
        phi_[1] * W * P[1 * 4 + 0] * W * phi_[0].transpose() + phi_[0] * W * P[0 * 4 + 1] * W * phi_[1].transpose();
    twist_rhs_.push_back(V_.transpose() * Rt * V_);
    dirichlet_rhs_.push_back(V_.transpose() * Rd * V_);
  }
}

std::vector<Eigen::MatrixXd> ContinuumProblem::coefficients(double mu) const {
  std::vector<Eigen::MatrixXd> out;
  const auto k = lambda_.size();
  for (size_t c = 0; c < twist_rhs_.size(); ++c) {
    Eigen::MatrixXd Y(k, k);
    for (Eigen::Index i = 0; i < k; ++i)
      for (Eigen::Index j = 0; j < k; ++j)
        Y(i, j) = -(twist_rhs_[c](i, j) + mu * dirichlet_rhs_[c](i, j)) /
                  (lambda_(i) * lambda_(j) + mu * (lambda_(i) + lambda_(j)));
    out.push_back(V_ * Y * V_.transpose());
  }
  return out;
}

double ContinuumProblem::energy(double mu, const std::vector<EnergyTerm>& terms) const {
  const std::vector<Eigen::MatrixXd> C = coefficients(mu);
  double e = 0;
  for (const EnergyTerm& t : terms) {
    if (t.a > kMaxOrder || t.b > kMaxOrder) continue;  // a derivative beyond third order: not needed
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd D = base_[size_t(c)][size_t(t.a) * 4 + size_t(t.b)];
      if (!C.empty()) D += phi_[size_t(t.a)].transpose() * C[size_t(c)] * phi_[size_t(t.b)];
      e += t.weight * weighted_square(D, weights_);
    }
  }
  return e;
}

Eigen::RowVector3d ContinuumProblem::evaluate(double mu, double u, double v) const {
  Eigen::RowVector3d p = coons::evaluate(coons_, u, v);
  if (degree_ < 2) return p;
  const std::vector<Eigen::MatrixXd> C = coefficients(mu);
  const Eigen::VectorXd fu = bubbles(degree_, Eigen::VectorXd::Constant(1, u))[0].col(0);
  const Eigen::VectorXd fv = bubbles(degree_, Eigen::VectorXd::Constant(1, v))[0].col(0);
  for (int c = 0; c < 3; ++c) p(c) += fu.dot(C[size_t(c)] * fv);
  return p;
}

bool ContinuumOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (!(mu_lower > 0 && mu_upper > mu_lower)) return fail("need 0 < mu_lower < mu_upper");
  if (scan_points < 3) return fail("scan_points must be >= 3");
  if (!(flat_tolerance >= 0)) return fail("flat_tolerance must be >= 0");
  return true;
}

const char* to_string(ContinuumStatus status) {
  switch (status) {
    case ContinuumStatus::kSuccess:
      return "success";
    case ContinuumStatus::kFlat:
      return "flat";
    case ContinuumStatus::kAtBound:
      return "at_bound";
  }
  return "unknown";
}

ContinuumOptimum continuum_optimum(const ContinuumProblem& problem, const std::vector<EnergyTerm>& terms,
                                   const ContinuumOptions& options) {
  ContinuumOptimum out;
  out.degree = problem.degree();
  out.scan.emplace_back(0.0, problem.energy(0, terms));
  const double l0 = std::log(options.mu_lower), l1 = std::log(options.mu_upper);
  for (int k = 0; k < options.scan_points; ++k) {
    const double mu = std::exp(l0 + (l1 - l0) * k / (options.scan_points - 1));
    out.scan.emplace_back(mu, problem.energy(mu, terms));
  }
  size_t best = 0;
  double lo = out.scan[0].second, hi = lo;
  for (size_t k = 0; k < out.scan.size(); ++k) {
    if (out.scan[k].second < out.scan[best].second) best = k;
    lo = std::min(lo, out.scan[k].second);
    hi = std::max(hi, out.scan[k].second);
  }
  out.value = out.scan[best].second;
  // the floor: an energy of order one of the boundary, times the terms' weights
  double weight = 0;
  for (const EnergyTerm& t : terms) weight = std::max(weight, std::abs(t.weight));
  if (hi - lo <= options.flat_tolerance * std::max(std::abs(hi), weight * problem.energy_scale())) {
    out.status = ContinuumStatus::kFlat;
    return out;
  }
  if (best <= 1 || best + 1 == out.scan.size()) {  // μ = 0, the smallest positive μ, or the upper bound
    out.status = ContinuumStatus::kAtBound;
    return out;
  }
  auto f = [&](double log_mu) { return problem.energy(std::exp(log_mu), terms); };
  const auto [x, value] = boost::math::tools::brent_find_minima(f, std::log(out.scan[best - 1].first),
                                                                std::log(out.scan[best + 1].first), 50);
  out.mu = std::exp(x);
  out.value = value;
  return out;
}

std::optional<double> exact_energy_mu(const ControlNet& net) {
  const int m = net.m, n = net.n;
  if (m < 2 || n < 2) return std::nullopt;
  auto difference = [](int k) {
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(k, k + 1);
    for (int i = 0; i < k; ++i) {
      D(i, i) = -k;
      D(i, i + 1) = k;
    }
    return D;
  };
  const Eigen::MatrixXd Du = difference(m), Dv = difference(n);
  const Eigen::MatrixXd Gm = bernstein_gram(m), Gm1 = bernstein_gram(m - 1), Gn = bernstein_gram(n),
                        Gn1 = bernstein_gram(n - 1);
  double tw_d = 0, d_d = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd B = coordinate_grid(net, c);
    const Eigen::MatrixXd g_tw = 2 * Du.transpose() * Gm1 * (Du * B * Dv.transpose()) * Gn1 * Dv;
    const Eigen::MatrixXd g_d = 2 * Du.transpose() * Gm1 * Du * B * Gn + 2 * Gm * B * Dv.transpose() * Gn1 * Dv;
    const auto ti = g_tw.block(1, 1, m - 1, n - 1);
    const auto di = g_d.block(1, 1, m - 1, n - 1);
    tw_d += ti.cwiseProduct(di).sum();
    d_d += di.squaredNorm();
  }
  if (!(d_d > 0)) return std::nullopt;
  return -tw_d / d_d;
}

}  // namespace coons
