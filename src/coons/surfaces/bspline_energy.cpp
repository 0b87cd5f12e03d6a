#include "coons/surfaces/bspline_energy.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace coons {

std::pair<Eigen::VectorXd, Eigen::VectorXd> gauss_legendre_unit(int k) {
  // Jacobi matrix of the Legendre polynomials on [−1, 1]: off-diagonal i / sqrt(4i² − 1).
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(k, k);
  for (int i = 1; i < k; ++i) {
    const double b = i / std::sqrt(4.0 * i * i - 1.0);
    J(i, i - 1) = b;
    J(i - 1, i) = b;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(J);
  Eigen::VectorXd nodes(k), weights(k);
  for (int i = 0; i < k; ++i) {
    nodes(i) = (eig.eigenvalues()(i) + 1.0) / 2.0;
    const double v = eig.eigenvectors()(0, i);
    weights(i) = v * v;  // 2 v² on [−1, 1], halved on [0, 1]
  }
  return {nodes, weights};
}

Eigen::MatrixXd bspline_gram(const Eigen::VectorXd& knots, int degree, int order) {
  const int count = int(knots.size()) - degree - 1;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(count, count);
  if (order > degree) return G;
  const auto [nodes, weights] = gauss_legendre_unit(degree + 1);
  for (int span = degree; span < count; ++span) {
    const double a = knots(span), b = knots(span + 1);
    if (!(b > a)) continue;
    for (Eigen::Index g = 0; g < nodes.size(); ++g) {
      const double t = a + (b - a) * nodes(g);
      const Eigen::MatrixXd N = basis_derivatives(knots, degree, span, t, order);
      const double w = (b - a) * weights(g);
      for (int r = 0; r <= degree; ++r)
        for (int c = 0; c <= degree; ++c) G(span - degree + r, span - degree + c) += w * N(order, r) * N(order, c);
    }
  }
  return G;
}

namespace {

// Coordinate c of a net as a #count_u by #count_v matrix.
Eigen::MatrixXd coordinate(const ControlNet& net, int c) {
  Eigen::MatrixXd X(net.m + 1, net.n + 1);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) X(i, j) = net.at(i, j)(c);
  return X;
}

}  // namespace

double bspline_energy_form(const BSplineSurface& s, const ControlNet& X, const ControlNet& Y, int a, int b) {
  if (a > s.degree_u || b > s.degree_v) return 0.0;
  const Eigen::MatrixXd Gu = bspline_gram(s.knots_u, s.degree_u, a);
  const Eigen::MatrixXd Gv = bspline_gram(s.knots_v, s.degree_v, b);
  double sum = 0;
  for (int c = 0; c < 3; ++c) sum += (Gu * coordinate(X, c) * Gv).cwiseProduct(coordinate(Y, c)).sum();
  return sum;
}

double bspline_energy(const BSplineSurface& s, int a, int b) { return bspline_energy_form(s, s.net, s.net, a, b); }

double bspline_combined_energy_form(const BSplineSurface& s, const ControlNet& X, const ControlNet& Y,
                                    const std::vector<BSplineEnergyTerm>& terms) {
  double sum = 0;
  for (const BSplineEnergyTerm& t : terms) sum += t.weight * bspline_energy_form(s, X, Y, t.a, t.b);
  return sum;
}

double bspline_combined_energy(const BSplineSurface& s, const std::vector<BSplineEnergyTerm>& terms) {
  return bspline_combined_energy_form(s, s.net, s.net, terms);
}

std::vector<BSplineEnergyTerm> bspline_twist_terms() { return {{1, 1, 1.0}}; }
std::vector<BSplineEnergyTerm> bspline_dirichlet_terms() { return {{1, 0, 1.0}, {0, 1, 1.0}}; }
std::vector<BSplineEnergyTerm> bspline_thin_plate_terms() { return {{2, 0, 1.0}, {1, 1, 2.0}, {0, 2, 1.0}}; }
std::vector<BSplineEnergyTerm> bspline_e3_terms() { return {{3, 0, 1.0}, {2, 1, 3.0}, {1, 2, 3.0}, {0, 3, 1.0}}; }

}  // namespace coons
