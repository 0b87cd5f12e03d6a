#include "coons/curves/bspline_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace coons {

namespace {

// The control points P_{k−p} … P_k that act on span k, as the start of de Boor's triangle.
std::vector<Eigen::RowVector3d> local_points(const BSplineCurve& c, int span) {
  std::vector<Eigen::RowVector3d> d(std::size_t(c.degree) + 1);
  for (int j = 0; j <= c.degree; ++j) d[std::size_t(j)] = c.points.row(span - c.degree + j);
  return d;
}

// de Boor's triangle with the parameter args[r − 1] at level r (all equal: evaluation).
Eigen::RowVector3d de_boor(const BSplineCurve& c, int span, const std::vector<double>& args) {
  const int p = c.degree;
  const Eigen::VectorXd& U = c.knots;
  std::vector<Eigen::RowVector3d> d = local_points(c, span);
  for (int r = 1; r <= p; ++r) {
    const double t = args[std::size_t(r) - 1];
    for (int j = p; j >= r; --j) {
      const double lo = U(j + span - p);
      const double hi = U(j + 1 + span - r);
      const double a = (t - lo) / (hi - lo);
      d[std::size_t(j)] = (1.0 - a) * d[std::size_t(j) - 1] + a * d[std::size_t(j)];
    }
  }
  return d[std::size_t(p)];
}

// the shortest text that reads back as x: two different knots never print alike ("{:g}" printed
// knot 10 of 0.99999999999999989 as "1", beside the last knot 1)
std::string number(double x) { return fmt::format("{}", x); }

}  // namespace

bool BSplineCurve::is_valid(std::string* why) const {
  const std::vector<KnotProblem> problems = knot_vector_problems(knots, degree, count());
  if (problems.empty()) return true;
  if (why != nullptr) *why = problems.front().reason;
  return false;
}

std::optional<KnotProblem> short_span_problem(const Eigen::VectorXd& knots) {
  const Eigen::Index last = knots.size() - 1;
  if (last < 1) return std::nullopt;
  const double range = knots(last) - knots(0);
  for (Eigen::Index i = 1; i <= last; ++i) {
    const double span = knots(i) - knots(i - 1);
    if (span > 0 && span < kMinKnotSpan * range)
      return KnotProblem{int(i), fmt::format("knot {} ({}) is {} after knot {} ({}), closer than {:g} of the knot "
                                             "range ({}): give the two knots one value (a repeated knot) or move "
                                             "them apart",
                                             i, fmt::format("{:.17g}", knots(i)), number(span), i - 1,
                                             fmt::format("{:.17g}", knots(i - 1)), kMinKnotSpan, number(range))};
  }
  return std::nullopt;
}

std::vector<KnotProblem> knot_vector_problems(const Eigen::VectorXd& knots, int degree, int count) {
  std::vector<KnotProblem> out;
  const int p = degree;
  if (p < 1) {
    out.push_back({-1, fmt::format("the degree is {}; it must be at least 1", p)});
    return out;
  }
  if (count < p + 1)
    out.push_back({-1, fmt::format("{} control points are too few for degree {} (at least {})", count, p, p + 1)});
  const Eigen::Index length = knots.size();
  if (length != Eigen::Index(count) + p + 1) {
    out.push_back({-1, fmt::format("{} knots given; points + degree + 1 = {} needed", length, count + p + 1)});
    return out;
  }
  bool finite_and_sorted = true;
  for (Eigen::Index i = 0; i < length; ++i) {
    if (!std::isfinite(knots(i))) {
      out.push_back({int(i), fmt::format("knot {} is not a finite number", i)});
      finite_and_sorted = false;
    } else if (i > 0 && std::isfinite(knots(i - 1)) && knots(i) < knots(i - 1)) {
      out.push_back({int(i), fmt::format("knot {} ({}) is smaller than knot {} ({}): knots must not decrease", i,
                                         number(knots(i)), i - 1, number(knots(i - 1)))});
      finite_and_sorted = false;
    }
  }
  if (!finite_and_sorted) return out;
  const Eigen::Index last = length - 1;
  if (!(knots(0) < knots(last))) {
    out.push_back(
        {int(last), fmt::format("knot {} ({}) equals knot 0: the domain is empty", last, number(knots(last)))});
    return out;
  }
  for (int i = 1; i <= p; ++i)
    if (knots(i) != knots(0))
      out.push_back({i, fmt::format("knot {} ({}) differs from knot 0 ({}): the first knot must be repeated "
                                    "degree + 1 = {} times (clamped)",
                                    i, number(knots(i)), number(knots(0)), p + 1)});
  if (knots(p + 1) == knots(0) && p + 1 < last)
    out.push_back({p + 1, fmt::format("knot {} repeats the first knot more than degree + 1 = {} times", p + 1, p + 1)});
  for (int i = 1; i <= p; ++i)
    if (knots(last - i) != knots(last))
      out.push_back({int(last - i), fmt::format("knot {} ({}) differs from knot {} ({}): the last knot must be "
                                                "repeated degree + 1 = {} times (clamped)",
                                                last - i, number(knots(last - i)), last, number(knots(last)), p + 1)});
  if (knots(last - p - 1) == knots(last) && last - p - 1 > 0)
    out.push_back({int(last - p - 1),
                   fmt::format("knot {} repeats the last knot more than degree + 1 = {} times", last - p - 1, p + 1)});
  // Interior knots: strictly between the first and the last value.
  int run = 0;
  for (Eigen::Index i = 0; i <= last; ++i) {
    const double u = knots(i);
    run = (i > 0 && u == knots(i - 1)) ? run + 1 : 1;
    if (u > knots(0) && u < knots(last) && run == p + 1)
      out.push_back({int(i), fmt::format("knot {} ({}) makes an interior knot repeat {} times; at most degree = {} "
                                         "allowed",
                                         i, number(u), run, p)});
  }
  if (auto problem = short_span_problem(knots)) out.push_back(std::move(*problem));
  return out;
}

int find_span(const Eigen::VectorXd& knots, int degree, double t) {
  const int n = int(knots.size()) - degree - 2;  // index of the last control point
  int k = 0;
  if (t >= knots(n + 1)) {
    k = n;
    while (k > degree && !(knots(k) < knots(k + 1))) --k;
    return k;
  }
  if (t < knots(degree)) {
    k = degree;
  } else {
    const double* first = knots.data() + degree;
    const double* past = knots.data() + n + 2;
    k = int(std::upper_bound(first, past, t) - knots.data()) - 1;
  }
  while (k < n && !(knots(k) < knots(k + 1))) ++k;
  return k;
}

namespace {

// A2.3 with the distances t − u_{span+1−j} and u_{span+j} − t given by distances(j) as a pair: the
// one recurrence of basis_derivatives and basis_derivatives_at_offset, which differ only in how
// they round those distances.
template <class Distances>
Eigen::MatrixXd basis_derivatives_from(int degree, int order, Distances distances) {
  const int p = degree;
  Eigen::MatrixXd ndu = Eigen::MatrixXd::Zero(p + 1, p + 1);
  Eigen::VectorXd left = Eigen::VectorXd::Zero(p + 1);
  Eigen::VectorXd right = Eigen::VectorXd::Zero(p + 1);
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    std::tie(left(j), right(j)) = distances(j);
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu(j, r) = right(r + 1) + left(j - r);  // a knot difference, positive on a non-empty span
      const double temp = ndu(r, j - 1) / ndu(j, r);
      ndu(r, j) = saved + right(r + 1) * temp;
      saved = left(j - r) * temp;
    }
    ndu(j, j) = saved;
  }
  Eigen::MatrixXd ders = Eigen::MatrixXd::Zero(order + 1, p + 1);
  for (int j = 0; j <= p; ++j) ders(0, j) = ndu(j, p);
  const int top = std::min(order, p);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2, p + 1);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a.setZero();
    a(0, 0) = 1.0;
    for (int k = 1; k <= top; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        d = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        d += a(s2, j) * ndu(rk + j, pk);
      }
      if (r <= pk) {
        a(s2, k) = -a(s1, k - 1) / ndu(pk + 1, r);
        d += a(s2, k) * ndu(r, pk);
      }
      ders(k, r) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= top; ++k) {
    ders.row(k) *= factor;
    factor *= p - k;
  }
  return ders;
}

}  // namespace

Eigen::MatrixXd basis_derivatives(const Eigen::VectorXd& knots, int degree, int span, double t, int order) {
  return basis_derivatives_from(degree, order,
                                [&](int j) { return std::pair(t - knots(span + 1 - j), knots(span + j) - t); });
}

Eigen::MatrixXd basis_derivatives_at_offset(const Eigen::VectorXd& knots, int degree, int span, double delta,
                                            int order) {
  return basis_derivatives_from(degree, order, [&](int j) {
    return std::pair((knots(span) - knots(span + 1 - j)) + delta, (knots(span + j) - knots(span)) - delta);
  });
}

Eigen::VectorXd basis_functions(const Eigen::VectorXd& knots, int degree, int count, double t) {
  Eigen::VectorXd N = Eigen::VectorXd::Zero(count);
  const int span = find_span(knots, degree, t);
  const Eigen::MatrixXd local = basis_derivatives(knots, degree, span, t, 0);
  for (int j = 0; j <= degree; ++j) N(span - degree + j) = local(0, j);
  return N;
}

Eigen::RowVector3d evaluate(const BSplineCurve& c, double t) {
  const int span = find_span(c.knots, c.degree, t);
  return de_boor(c, span, std::vector<double>(std::size_t(std::max(c.degree, 0)), t));
}

BSplineCurve derivative_curve(const BSplineCurve& c) {
  const int p = c.degree;
  const int count = c.count();
  BSplineCurve d;
  d.degree = p - 1;
  d.knots = c.knots.segment(1, c.knots.size() - 2);
  d.points = Eigen::MatrixX3d::Zero(std::max(count - 1, 1), 3);
  for (int i = 0; i + 1 < count; ++i) {
    const double h = c.knots(i + p + 1) - c.knots(i + 1);
    // h = 0 only where the basis function of the new point vanishes (a knot of full multiplicity).
    if (h > 0) d.points.row(i) = double(p) * (c.points.row(i + 1) - c.points.row(i)) / h;
  }
  return d;
}

Eigen::RowVector3d evaluate_derivative(const BSplineCurve& c, int r, double t) {
  if (r > c.degree) return Eigen::RowVector3d::Zero();
  BSplineCurve d = c;
  for (int k = 0; k < r; ++k) d = derivative_curve(d);
  return evaluate(d, t);
}

Eigen::RowVector3d blossom(const BSplineCurve& c, int span, const std::vector<double>& args) {
  return de_boor(c, span, args);
}

BSplineCurve inserted_knot(const BSplineCurve& c, double t, int times) {
  BSplineCurve out = c;
  if (!(t > c.start() && t < c.end())) return out;
  const int p = c.degree;
  for (int step = 0; step < times; ++step) {
    const Eigen::VectorXd& U = out.knots;
    const int multiplicity = int(std::count(U.data(), U.data() + U.size(), t));
    if (multiplicity >= p) break;
    const int k = find_span(U, p, t);
    const int count = out.count();
    Eigen::MatrixX3d Q(count + 1, 3);
    for (int i = 0; i <= k - p; ++i) Q.row(i) = out.points.row(i);
    for (int i = k - p + 1; i <= k; ++i) {
      const double a = (t - U(i)) / (U(i + p) - U(i));
      Q.row(i) = a * out.points.row(i) + (1.0 - a) * out.points.row(i - 1);
    }
    for (int i = k + 1; i <= count; ++i) Q.row(i) = out.points.row(i - 1);
    Eigen::VectorXd V(U.size() + 1);
    V.head(k + 1) = U.head(k + 1);
    V(k + 1) = t;
    V.tail(U.size() - k - 1) = U.tail(U.size() - k - 1);
    out.knots = std::move(V);
    out.points = std::move(Q);
  }
  return out;
}

BSplineCurve refined(const BSplineCurve& c, const std::vector<double>& knots) {
  BSplineCurve out = c;
  for (double t : knots) out = inserted_knot(out, t, 1);
  return out;
}

namespace {

// One degree step: multiplicities + 1, points = averaged blossoms of the degree-p pieces.
BSplineCurve elevated_once(const BSplineCurve& c) {
  const int p = c.degree;
  std::vector<double> V;
  for (const auto& [u, s] : knot_multiplicities(c.knots)) V.insert(V.end(), std::size_t(s) + 1, u);
  const int count = int(V.size()) - (p + 1) - 1;
  BSplineCurve out;
  out.degree = p + 1;
  out.knots = Eigen::Map<const Eigen::VectorXd>(V.data(), Eigen::Index(V.size()));
  out.points.resize(count, 3);
  for (int i = 0; i < count; ++i) {
    // Any non-empty span i ≤ j ≤ i + p + 1 gives Q_i; the one nearest the middle of the arguments
    // extrapolates least (measured, degree 5 raised by 2: 4e-15 against 4e-12 with the first span).
    int j = -1;
    for (int k = i; k <= i + p + 1; ++k)
      if (V[std::size_t(k)] < V[std::size_t(k) + 1] &&
          (j < 0 || std::abs(2 * k - (2 * i + p + 1)) < std::abs(2 * j - (2 * i + p + 1))))
        j = k;
    const int span = find_span(c.knots, p, 0.5 * (V[std::size_t(j)] + V[std::size_t(j) + 1]));
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (int drop = 0; drop <= p; ++drop) {
      std::vector<double> args;
      for (int a = 0; a <= p; ++a)
        if (a != drop) args.push_back(V[std::size_t(i) + 1 + std::size_t(a)]);
      sum += blossom(c, span, args);
    }
    out.points.row(i) = sum / double(p + 1);
  }
  return out;
}

}  // namespace

BSplineCurve degree_elevated(const BSplineCurve& c, int degree) {
  BSplineCurve out = c;
  while (out.degree < degree) out = elevated_once(out);
  return out;
}

Eigen::VectorXd greville_abscissae(const BSplineCurve& c) {
  const int p = c.degree;
  Eigen::VectorXd xi(c.count());
  for (int i = 0; i < c.count(); ++i) xi(i) = c.knots.segment(i + 1, p).sum() / double(p);
  // The ends exactly (the sum of p equal knots divided by p may round).
  xi(0) = c.start();
  xi(c.count() - 1) = c.end();
  return xi;
}

BSplineCurve reparametrised(const BSplineCurve& c, double a, double b) {
  BSplineCurve out = c;
  const double s = (b - a) / (c.end() - c.start());
  for (Eigen::Index i = 0; i < c.knots.size(); ++i) out.knots(i) = a + (c.knots(i) - c.start()) * s;
  out.knots(0) = a;
  out.knots(out.knots.size() - 1) = b;
  for (int i = 1; i <= c.degree; ++i) {
    out.knots(i) = a;
    out.knots(out.knots.size() - 1 - i) = b;
  }
  return out;
}

std::vector<std::pair<double, int>> knot_multiplicities(const Eigen::VectorXd& knots) {
  std::vector<std::pair<double, int>> out;
  for (Eigen::Index i = 0; i < knots.size(); ++i) {
    if (!out.empty() && out.back().first == knots(i))
      ++out.back().second;
    else
      out.emplace_back(knots(i), 1);
  }
  return out;
}

}  // namespace coons
