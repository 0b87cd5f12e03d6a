#include "boolean_sum.h"

#include <algorithm>
#include <cassert>

namespace coons {

namespace {

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  double b = 1;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// de Casteljau on scalar coefficients.
double casteljau(Eigen::VectorXd b, double t) {
  for (Eigen::Index k = b.size() - 1; k >= 1; --k)
    for (Eigen::Index i = 0; i < k; ++i) b(i) = (1 - t) * b(i) + t * b(i + 1);
  return b.size() ? b(0) : 0.0;
}

}  // namespace

double Blend::value(int r, double t) const {
  const int k = degree();
  if (r > k) return 0;
  Eigen::VectorXd b = bernstein;
  double factor = 1;
  for (int d = 0; d < r; ++d) {
    factor *= k - d;
    b = (b.tail(b.size() - 1) - b.head(b.size() - 1)).eval();
  }
  return factor * casteljau(b, t);
}

Eigen::VectorXd Blend::bernstein_at(int k) const {
  assert(k >= degree());
  Eigen::VectorXd q = bernstein;
  for (int d = degree(); d < k; ++d) {  // d → d + 1
    Eigen::VectorXd r(d + 2);
    r(0) = q(0);
    r(d + 1) = q(d);
    for (int i = 1; i <= d; ++i) {
      const double a = double(i) / (d + 1);
      r(i) = a * q(i - 1) + (1 - a) * q(i);
    }
    q = std::move(r);
  }
  return q;
}

Blend Blend::from_monomial(const std::vector<double>& c) {
  // b_i = Σ_{j ≤ i} C(i, j)/C(n, j) c_j.
  const int n = int(c.size()) - 1;
  Blend out;
  out.bernstein = Eigen::VectorXd::Zero(n + 1);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= i; ++j) out.bernstein(i) += binomial(i, j) / binomial(n, j) * c[j];
  return out;
}

Blend linear_blend(int i) {
  return Blend::from_monomial(i == 0 ? std::vector<double>{1, -1} : std::vector<double>{0, 1});
}

Blend hermite_blend(int i) {
  switch (i) {
    case 0:
      return Blend::from_monomial({1, 0, -3, 2});
    case 1:
      return Blend::from_monomial({0, 0, 3, -2});
    case 2:
      return Blend::from_monomial({0, 1, -2, 1});
    default:
      return Blend::from_monomial({0, 0, -1, 1});
  }
}

SurfacePoint evaluate(const BooleanSum& sum, double u, double v) {
  Eigen::RowVector3d d[3][3];  // d[a][b] = ∂^a_u ∂^b_v r, a + b ≤ 2
  for (auto& row : d)
    for (auto& x : row) x.setZero();
  for (const auto& term : sum.u_blended) {
    const Eigen::RowVector3d X[3] = {term.curve.derivative(0, v), term.curve.derivative(1, v),
                                     term.curve.derivative(2, v)};
    for (int a = 0; a <= 2; ++a) {
      const double w = term.blend.value(a, u);
      if (w == 0) continue;
      for (int b = 0; a + b <= 2; ++b) d[a][b] += w * X[b];
    }
  }
  for (const auto& term : sum.v_blended) {
    const Eigen::RowVector3d Y[3] = {term.curve.derivative(0, u), term.curve.derivative(1, u),
                                     term.curve.derivative(2, u)};
    for (int b = 0; b <= 2; ++b) {
      const double w = term.blend.value(b, v);
      if (w == 0) continue;
      for (int a = 0; a + b <= 2; ++a) d[a][b] += w * Y[a];
    }
  }
  for (size_t k = 0; k < sum.tensor_u.size(); ++k)
    for (size_t l = 0; l < sum.tensor_v.size(); ++l)
      for (int a = 0; a <= 2; ++a)
        for (int b = 0; a + b <= 2; ++b)
          d[a][b] += sum.tensor_u[k].value(a, u) * sum.tensor_v[l].value(b, v) * sum.tensor[k][l];
  SurfacePoint s;
  s.p = d[0][0];
  s.du = d[1][0];
  s.dv = d[0][1];
  s.duu = d[2][0];
  s.duv = d[1][1];
  s.dvv = d[0][2];
  return s;
}

std::optional<ControlNet> bezier_net(const BooleanSum& sum) {
  int m = 1, n = 1;
  for (const auto& t : sum.u_blended) {
    if (!t.curve.bezier()) return std::nullopt;
    m = std::max(m, t.blend.degree());
    n = std::max(n, t.curve.bezier()->degree());
  }
  for (const auto& t : sum.v_blended) {
    if (!t.curve.bezier()) return std::nullopt;
    m = std::max(m, t.curve.bezier()->degree());
    n = std::max(n, t.blend.degree());
  }
  for (const auto& b : sum.tensor_u) m = std::max(m, b.degree());
  for (const auto& b : sum.tensor_v) n = std::max(n, b.degree());

  ControlNet net(m, n);
  for (const auto& t : sum.u_blended) {
    const Eigen::VectorXd a = t.blend.bernstein_at(m);
    const Eigen::MatrixX3d X = elevated(*t.curve.bezier(), n).points;
    for (int i = 0; i <= m; ++i)
      for (int j = 0; j <= n; ++j) net.at(i, j) += a(i) * X.row(j);
  }
  for (const auto& t : sum.v_blended) {
    const Eigen::VectorXd b = t.blend.bernstein_at(n);
    const Eigen::MatrixX3d Y = elevated(*t.curve.bezier(), m).points;
    for (int i = 0; i <= m; ++i)
      for (int j = 0; j <= n; ++j) net.at(i, j) += b(j) * Y.row(i);
  }
  for (size_t k = 0; k < sum.tensor_u.size(); ++k) {
    const Eigen::VectorXd s = sum.tensor_u[k].bernstein_at(m);
    for (size_t l = 0; l < sum.tensor_v.size(); ++l) {
      const Eigen::VectorXd t = sum.tensor_v[l].bernstein_at(n);
      for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) net.at(i, j) += s(i) * t(j) * sum.tensor[k][l];
    }
  }
  return net;
}

}  // namespace coons
