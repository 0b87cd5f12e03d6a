#include "bernstein.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace coons {

Eigen::VectorXd bernstein_basis(int k, double t) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(k + 1);
  if (k > kDeCasteljauMaxDegree && t >= 0 && t <= 1) {
    // From the largest value, at i* = ⌊(k+1)t⌋, outwards by the ratios of neighbours; past 1e−308
    // of the peak a value is 0. No power of t or 1 − t is formed, so nothing under- or overflows.
    if (t == 0 || t == 1) {
      b(t == 0 ? 0 : k) = 1;
      return b;
    }
    const int peak = std::min(int(std::floor((k + 1) * t)), k);
    const double up = t / (1 - t), down = (1 - t) / t;
    b(peak) = 1;
    for (int i = peak; i < k && b(i) > 0; ++i) b(i + 1) = b(i) * (double(k - i) / double(i + 1) * up);
    for (int i = peak; i > 0 && b(i) > 0; --i) b(i - 1) = b(i) * (double(i) / double(k - i + 1) * down);
    return b / b.sum();  // Σ B_i^k = 1
  }
  b(0) = 1;
  const double s = 1 - t;
  for (int d = 1; d <= k; ++d) {
    for (int i = d; i >= 1; --i) b(i) = s * b(i) + t * b(i - 1);
    b(0) *= s;
  }
  return b;
}

BernsteinGramEntries::BernsteinGramEntries(int k) : k_(k), log_form_(k > 510) {
  if (!log_form_) {
    // Pascal's rule in double: exact up to 2^53 (k ≤ 26), relative error ~k·ε beyond; C(1020, 510)
    // still fits in a double.
    ck_.assign(k + 1, 0.0);
    c2k_.assign(2 * k + 1, 0.0);
    ck_[0] = c2k_[0] = 1;
    for (int r = 1; r <= 2 * k; ++r)
      for (int i = r; i >= 1; --i) c2k_[i] += c2k_[i - 1];
    for (int r = 1; r <= k; ++r)
      for (int i = r; i >= 1; --i) ck_[i] += ck_[i - 1];
    return;
  }
  // Beyond, log-binomials (relative error ~1e-12 at k ≈ 1000).
  auto log_binomial = [](int n, int i) {
    return std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0);
  };
  ck_.resize(k + 1);
  c2k_.resize(2 * k + 1);
  for (int i = 0; i <= k; ++i) ck_[i] = log_binomial(k, i);
  for (int r = 0; r <= 2 * k; ++r) c2k_[r] = log_binomial(2 * k, r);
}

double BernsteinGramEntries::operator()(int i, int l) const {
  if (i > l) std::swap(i, l);  // the upper triangle's expression, so that G is exactly symmetric
  if (!log_form_) return ck_[i] * (ck_[l] / c2k_[i + l]) / (2 * k_ + 1);
  return std::exp(ck_[i] + ck_[l] - c2k_[i + l]) / (2 * k_ + 1);
}

Eigen::MatrixXd bernstein_gram(int k) {
  const BernsteinGramEntries entry(k);
  Eigen::MatrixXd G(k + 1, k + 1);
  for (int i = 0; i <= k; ++i)
    for (int l = i; l <= k; ++l) G(i, l) = G(l, i) = entry(i, l);
  return G;
}

Eigen::MatrixXd coordinate_grid(const ControlNet& net, int c) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(net.points.col(c).data(), net.m + 1, net.n + 1);
}

ControlNet derivative_net(const ControlNet& net, int a, int b) {
  if (a > net.m || b > net.n) return ControlNet(0, 0);
  double factor = 1;
  for (int r = 0; r < a; ++r) factor *= net.m - r;
  for (int r = 0; r < b; ++r) factor *= net.n - r;
  ControlNet out(net.m - a, net.n - b);
  for (int c = 0; c < 3; ++c) {
    Eigen::MatrixXd P = coordinate_grid(net, c);
    for (int r = 0; r < a; ++r) P = (P.bottomRows(P.rows() - 1) - P.topRows(P.rows() - 1)).eval();
    for (int r = 0; r < b; ++r) P = (P.rightCols(P.cols() - 1) - P.leftCols(P.cols() - 1)).eval();
    for (int i = 0; i <= out.m; ++i)
      for (int j = 0; j <= out.n; ++j) out.at(i, j)(c) = factor * P(i, j);
  }
  return out;
}

Eigen::RowVector3d evaluate(const ControlNet& net, double u, double v) {
  const Eigen::VectorXd bu = bernstein_basis(net.m, u), bv = bernstein_basis(net.n, v);
  Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) p += bu(i) * bv(j) * net.at(i, j);
  return p;
}

Eigen::RowVector3d evaluate_derivative(const ControlNet& net, int a, int b, double u, double v) {
  return evaluate(derivative_net(net, a, b), u, v);
}

Eigen::MatrixX3d sample_surface(const ControlNet& net, int ku, int kv) {
  Eigen::MatrixXd Bu(ku, net.m + 1), Bv(kv, net.n + 1);
  for (int s = 0; s < ku; ++s) Bu.row(s) = bernstein_basis(net.m, double(s) / (ku - 1)).transpose();
  for (int t = 0; t < kv; ++t) Bv.row(t) = bernstein_basis(net.n, double(t) / (kv - 1)).transpose();
  Eigen::MatrixX3d out(Eigen::Index(ku) * kv, 3);
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd S = Bu * coordinate_grid(net, c) * Bv.transpose();  // ku by kv
    for (int s = 0; s < ku; ++s)
      for (int t = 0; t < kv; ++t) out(Eigen::Index(s) * kv + t, c) = S(s, t);
  }
  return out;
}

}  // namespace coons
