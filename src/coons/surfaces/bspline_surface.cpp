#include "coons/surfaces/bspline_surface.h"

#include <algorithm>
#include <cstddef>
#include <map>
#include <utility>

#include "coons/net/coons_net.h"

namespace coons {

bool BSplineSurface::is_valid(std::string* why) const {
  const int count_u = net.m + 1;
  const int count_v = net.n + 1;
  if (net.points.rows() != Eigen::Index(count_u) * count_v) {
    if (why != nullptr) *why = "the net has the wrong number of points";
    return false;
  }
  for (int direction = 0; direction < 2; ++direction) {
    const auto problems = direction == 0 ? knot_vector_problems(knots_u, degree_u, count_u)
                                         : knot_vector_problems(knots_v, degree_v, count_v);
    if (!problems.empty()) {
      if (why != nullptr) *why = std::string(direction == 0 ? "knots_u: " : "knots_v: ") + problems.front().reason;
      return false;
    }
  }
  return true;
}

Eigen::RowVector3d evaluate_derivative(const BSplineSurface& s, int a, int b, double u, double v) {
  const int p = s.degree_u;
  const int q = s.degree_v;
  if (a > p || b > q) return Eigen::RowVector3d::Zero();
  const int span_u = find_span(s.knots_u, p, u);
  const int span_v = find_span(s.knots_v, q, v);
  const Eigen::MatrixXd Nu = basis_derivatives(s.knots_u, p, span_u, u, a);
  const Eigen::MatrixXd Nv = basis_derivatives(s.knots_v, q, span_v, v, b);
  Eigen::RowVector3d out = Eigen::RowVector3d::Zero();
  for (int k = 0; k <= p; ++k) {
    Eigen::RowVector3d column = Eigen::RowVector3d::Zero();
    for (int l = 0; l <= q; ++l) column += Nv(b, l) * s.net.at(span_u - p + k, span_v - q + l);
    out += Nu(a, k) * column;
  }
  return out;
}

Eigen::RowVector3d evaluate(const BSplineSurface& s, double u, double v) { return evaluate_derivative(s, 0, 0, u, v); }

BSplineBoundary boundary_of(const BSplineSurface& s) {
  const Boundary frame = boundary_of(s.net);
  return {BSplineCurve(s.degree_u, s.knots_u, frame.bottom), BSplineCurve(s.degree_u, s.knots_u, frame.top),
          BSplineCurve(s.degree_v, s.knots_v, frame.left), BSplineCurve(s.degree_v, s.knots_v, frame.right)};
}

namespace {

// Each knot of b (over [0, 1]) within kSameKnot of one of a's takes a's value. Valid vectors keep
// their distinct knots kMinKnotSpan apart, so no two of b's knots meet and their order holds.
void snap_knots(const BSplineCurve& a, BSplineCurve& b) {
  const double* first = a.knots.data();
  const double* past = first + a.knots.size();
  for (Eigen::Index i = 0; i < b.knots.size(); ++i) {
    double& u = b.knots(i);
    const double* above = std::lower_bound(first, past, u);
    if (above != past && *above - u <= kSameKnot) {
      u = *above;
    } else if (above != first && u - *(above - 1) <= kSameKnot) {
      u = *(above - 1);
    }
  }
}

// Both curves over [0, 1] at the higher degree, then with the union of their knots (each value at
// its larger multiplicity).
void make_pair_compatible(BSplineCurve& a, BSplineCurve& b, const char* name_a, const char* name_b,
                          std::vector<CompatibilityNote>* notes) {
  const int degree_a = a.degree;
  const int degree_b = b.degree;
  a = reparametrised(a, 0.0, 1.0);
  b = reparametrised(b, 0.0, 1.0);
  snap_knots(a, b);
  const int p = std::max(a.degree, b.degree);
  a = degree_elevated(a, p);
  b = degree_elevated(b, p);
  const Eigen::Index knots_a = a.knots.size();
  const Eigen::Index knots_b = b.knots.size();
  std::map<double, std::pair<int, int>> union_knots;
  for (const auto& [u, s] : knot_multiplicities(a.knots)) union_knots[u].first = s;
  for (const auto& [u, s] : knot_multiplicities(b.knots)) union_knots[u].second = s;
  for (const auto& [u, s] : union_knots) {
    const int target = std::max(s.first, s.second);
    if (s.first < target) a = inserted_knot(a, u, target - s.first);
    if (s.second < target) b = inserted_knot(b, u, target - s.second);
  }
  if (notes == nullptr) return;
  const auto note = [&](const char* name, int raised, Eigen::Index inserted) {
    if (raised > 0 || inserted > 0) notes->push_back({name, raised, int(inserted)});
  };
  note(name_a, p - degree_a, a.knots.size() - knots_a);
  note(name_b, p - degree_b, b.knots.size() - knots_b);
}

Eigen::RowVector3d at_normalised(const BSplineCurve& c, double s) {
  return evaluate(c, c.start() + s * (c.end() - c.start()));
}

}  // namespace

BSplineBoundary compatible_boundary(const BSplineBoundary& b, std::vector<CompatibilityNote>* notes) {
  BSplineBoundary out = b;
  make_pair_compatible(out.bottom, out.top, "bottom", "top", notes);
  make_pair_compatible(out.left, out.right, "left", "right", notes);
  return out;
}

std::optional<std::string> merged_span_problem(const BSplineBoundary& compatible, int direction) {
  const bool u = direction == 0;
  const auto problem = short_span_problem(u ? compatible.bottom.knots : compatible.left.knots);
  if (!problem) return std::nullopt;
  return std::string(u ? "the knots of bottom and top" : "the knots of left and right") +
         " together, over [0, 1]: " + problem->reason;
}

BSplineSurface greville_coons_surface(const BSplineBoundary& b) {
  BSplineSurface s;
  s.degree_u = b.bottom.degree;
  s.degree_v = b.left.degree;
  s.knots_u = b.bottom.knots;
  s.knots_v = b.left.knots;
  const int count_u = b.bottom.count();
  const int count_v = b.left.count();
  // Greville abscissae on [0, 1] are the blending parameters (linear precision, docs/math.md §10);
  // boolean_sum_net takes the weights of the left and the bottom side, 1 − ξ_i and 1 − η_j.
  const Eigen::VectorXd xi = greville_abscissae(reparametrised(b.bottom, 0.0, 1.0));
  const Eigen::VectorXd eta = greville_abscissae(reparametrised(b.left, 0.0, 1.0));
  std::vector<double> w_u(static_cast<std::size_t>(count_u));
  std::vector<double> w_v(static_cast<std::size_t>(count_v));
  for (int i = 0; i < count_u; ++i) w_u[std::size_t(i)] = 1.0 - xi(i);
  for (int j = 0; j < count_v; ++j) w_v[std::size_t(j)] = 1.0 - eta(j);
  Boundary frame;
  frame.m = count_u - 1;
  frame.n = count_v - 1;
  frame.bottom = b.bottom.points;
  frame.top = b.top.points;
  frame.left = b.left.points;
  frame.right = b.right.points;
  s.net = boolean_sum_net(frame, w_u, w_v);
  return s;
}

Eigen::RowVector3d coons_patch_point(const BSplineBoundary& b, double u, double v) {
  const Eigen::RowVector3d b00 = at_normalised(b.bottom, 0.0);
  const Eigen::RowVector3d b10 = at_normalised(b.bottom, 1.0);
  const Eigen::RowVector3d b01 = at_normalised(b.top, 0.0);
  const Eigen::RowVector3d b11 = at_normalised(b.top, 1.0);
  return (1 - v) * at_normalised(b.bottom, u) + v * at_normalised(b.top, u) + (1 - u) * at_normalised(b.left, v) +
         u * at_normalised(b.right, v) -
         ((1 - u) * (1 - v) * b00 + u * (1 - v) * b10 + (1 - u) * v * b01 + u * v * b11);
}

}  // namespace coons
