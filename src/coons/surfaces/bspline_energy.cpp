#include "coons/surfaces/bspline_energy.h"

#include <Eigen/SparseCore>
#include <cmath>
#include <utility>
#include <vector>

#include "coons/curves/bspline_curve.h"
#include "coons/net/quadrature.h"

namespace coons {

Eigen::MatrixXd bspline_derivative_points(const Eigen::VectorXd& knots, int degree, const Eigen::MatrixXd& X, int a) {
  if (a > degree) return Eigen::MatrixXd(0, X.cols());
  Eigen::MatrixXd P = X;
  for (int k = 1; k <= a; ++k) {
    const Eigen::Index rows = P.rows() - 1;
    Eigen::MatrixXd next(rows, P.cols());
    for (Eigen::Index i = 0; i < rows; ++i) {
      const double span = knots(i + degree + 1) - knots(i + k);
      if (span > 0)
        next.row(i) = (double(degree - k + 1) / span) * (P.row(i + 1) - P.row(i));
      else
        next.row(i).setZero();  // N_{i+k,p−k} vanishes: its coefficient does not matter
    }
    P = std::move(next);
  }
  return P;
}

namespace {

// The basis of degree p − a on knots(a … end − a), where the a-th derivative's control points
// (bspline_derivative_points) live, at the Gauss–Legendre nodes of every non-empty span:
// values(node, i) = N_{i+a,p−a}(node) (p − a + 1 per row), weights the nodes' weights times the
// span's length.
struct Sampling {
  Eigen::SparseMatrix<double, Eigen::RowMajor> values;
  Eigen::VectorXd weights;
};

Sampling derivative_sampling(const Eigen::VectorXd& knots, int degree, int a) {
  const int q = degree - a;
  const Eigen::VectorXd trimmed = knots.segment(a, knots.size() - 2 * a);
  const int count = int(trimmed.size()) - q - 1;
  const QuadratureRule rule = gauss_legendre(q + 1);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> weights;
  for (int span = q; span < count; ++span) {
    const double lo = trimmed(span), hi = trimmed(span + 1);
    if (!(hi > lo)) continue;
    for (Eigen::Index g = 0; g < rule.nodes.size(); ++g) {
      const Eigen::MatrixXd N = basis_derivatives_at_offset(trimmed, q, span, (hi - lo) * rule.nodes(g), 0);
      const int row = int(weights.size());
      for (int r = 0; r <= q; ++r) entries.emplace_back(row, span - q + r, N(0, r));
      weights.push_back((hi - lo) * rule.weights(g));
    }
  }
  Sampling out;
  out.values.resize(Eigen::Index(weights.size()), count);
  out.values.setFromTriplets(entries.begin(), entries.end());
  out.weights = Eigen::Map<const Eigen::VectorXd>(weights.data(), Eigen::Index(weights.size()));
  return out;
}

// Coordinate c of a net as a #count_u by #count_v matrix.
Eigen::MatrixXd coordinate(const ControlNet& net, int c) {
  Eigen::MatrixXd X(net.m + 1, net.n + 1);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) X(i, j) = net.at(i, j)(c);
  return X;
}

// ∂^a_u ∂^b_v of coordinate X at the nodes (rows: u nodes, columns: v nodes).
Eigen::MatrixXd derivative_at_nodes(const BSplineSurface& s, const Sampling& u, const Sampling& v,
                                    const Eigen::MatrixXd& X, int a, int b) {
  const Eigen::MatrixXd along_u = bspline_derivative_points(s.knots_u, s.degree_u, X, a);
  const Eigen::MatrixXd both = bspline_derivative_points(s.knots_v, s.degree_v, along_u.transpose(), b).transpose();
  const Eigen::MatrixXd at_u = u.values * both;      // u nodes × (count_v − b)
  return (v.values * at_u.transpose()).transpose();  // u nodes × v nodes
}

}  // namespace

double bspline_energy_form(const BSplineSurface& s, const ControlNet& X, const ControlNet& Y, int a, int b) {
  if (a > s.degree_u || b > s.degree_v) return 0.0;
  const Sampling u = derivative_sampling(s.knots_u, s.degree_u, a);
  const Sampling v = derivative_sampling(s.knots_v, s.degree_v, b);
  const bool same = &X == &Y;
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd dx = derivative_at_nodes(s, u, v, coordinate(X, c), a, b);
    const Eigen::MatrixXd dy = same ? Eigen::MatrixXd() : derivative_at_nodes(s, u, v, coordinate(Y, c), a, b);
    const Eigen::MatrixXd& other = same ? dx : dy;
    sum += (u.weights.asDiagonal() * dx.cwiseProduct(other) * v.weights.asDiagonal()).sum();
  }
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
