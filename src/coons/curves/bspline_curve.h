// Clamped B-spline curves in R³ of any degree p ≥ 1 with non-uniform knots: knot-vector checks,
// evaluation (de Boor), derivatives (the derivative curve), the blossom, knot insertion (Boehm),
// exact degree elevation (by blossoming), Greville abscissae, reparametrisation of the domain.
// Sizes: #count by 3 control points, #count + p + 1 knots u_0 ≤ … ≤ u_{count+p}, the end knots
// repeated p + 1 times, so the curve runs over [u_p, u_count] = [u_0, u_{count+p}] and interpolates
// its first and last control points.
// Based on: L. Piegl, W. Tiller, The NURBS Book, 2nd ed. (1997), A2.1 (span), A2.2/A2.3 (basis and
// derivatives), §3.3 (derivative curve), A5.1 (knot insertion; W. Boehm, CAD 12, 1980);
// L. Ramshaw, Blossoms are polar forms, CAGD 6 (1989) and H.-P. Seidel, A new multiaffine approach
// to B-splines, CAGD 6 (1989) (control points are blossom values; degree elevation averages them).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace coons {

//! c(t) = Σ_i P_i N_{i,p}(t) on [knots(0), knots(last)].
struct BSplineCurve {
  int degree = 1;           //!< p ≥ 1
  Eigen::VectorXd knots;    //!< #count + p + 1, clamped
  Eigen::MatrixX3d points;  //!< #count by 3, count ≥ p + 1

  BSplineCurve() = default;
  BSplineCurve(int p, Eigen::VectorXd U, Eigen::MatrixX3d P) : degree(p), knots(std::move(U)), points(std::move(P)) {}

  [[nodiscard]] int count() const { return int(points.rows()); }
  [[nodiscard]] double start() const { return knots(0); }
  [[nodiscard]] double end() const { return knots(knots.size() - 1); }
  //! True when the knot vector is valid for the degree and the points (see knot_vector_problems);
  //! otherwise false with the first problem in *why (when why is not null).
  bool is_valid(std::string* why) const;
};

//! One violated rule of a knot vector; index is the knot blamed (−1: the vector as a whole).
struct KnotProblem {
  int index = -1;
  std::string reason;  //!< e.g. "knot 4 (0.2) is smaller than knot 3 (0.5)"
};

//! The shortest non-empty knot span accepted, as a fraction of the knot range. A shorter span is a
//! repeated knot to within rounding: the basis derivatives grow like 1/span and the Greville
//! abscissae around it coincide, so the nets and energies built on it lose their digits (a span of
//! 1e−15 of the range left a mask residual of 0.17 behind a solve that reported success).
inline constexpr double kMinKnotSpan = 1e-9;

//! The first non-empty span of a finite, non-decreasing `knots` shorter than kMinKnotSpan of
//! knots(last) − knots(0), blamed on its upper knot; std::nullopt when there is none.
std::optional<KnotProblem> short_span_problem(const Eigen::VectorXd& knots);

//! Every violated rule of a clamped knot vector for a curve of degree p with `count` control
//! points: p ≥ 1, count ≥ p + 1, length = count + p + 1, finite, non-decreasing, the first and the
//! last knot repeated exactly p + 1 times (with first < last), interior multiplicity ≤ p, no
//! non-empty span shorter than kMinKnotSpan of the range. Empty when the vector is valid.
std::vector<KnotProblem> knot_vector_problems(const Eigen::VectorXd& knots, int degree, int count);

//! The span index k with knots(k) ≤ t < knots(k + 1), p ≤ k ≤ count − 1; t at or beyond the end
//! gives the last non-empty span, t before the start the first (A2.1).
int find_span(const Eigen::VectorXd& knots, int degree, double t);

//! The p + 1 basis functions N_{k−p,p}(t) … N_{k,p}(t) that do not vanish on span k and their
//! derivatives: row r holds the r-th derivatives, r = 0 … order (rows above p are zero) (A2.3).
Eigen::MatrixXd basis_derivatives(const Eigen::VectorXd& knots, int degree, int span, double t, int order);

//! basis_derivatives at t = knots(span) + delta, the knot distances computed from delta
//! ((u_span − u_{span+1−j}) + delta), so a point keeps its relative position within a short span: t
//! itself would round to ulp(u_span), 1e−7 of a span of 1e−9 at 0.7 (bspline_energy's nodes).
Eigen::MatrixXd basis_derivatives_at_offset(const Eigen::VectorXd& knots, int degree, int span, double delta,
                                            int order);

//! All count basis functions at t (a dense vector; sums to 1 on the domain).
Eigen::VectorXd basis_functions(const Eigen::VectorXd& knots, int degree, int count, double t);

//! c(t) by de Boor's algorithm (t outside the domain extrapolates the end pieces).
Eigen::RowVector3d evaluate(const BSplineCurve& c, double t);

//! The derivative curve c′: degree p − 1, knots u_1 … u_{count+p−1}, points
//! p (P_{i+1} − P_i)/(u_{i+p+1} − u_{i+1}). For p = 1 the result is a degree-0 curve, which only
//! evaluate() and evaluate_derivative() accept.
BSplineCurve derivative_curve(const BSplineCurve& c);

//! d^r c / dt^r at t, r ≥ 0 (zero when r > p); at a knot the derivative from the right.
Eigen::RowVector3d evaluate_derivative(const BSplineCurve& c, int r, double t);

//! The blossom f(a_1, …, a_p) of the polynomial piece of c on span `span` (de Boor with one
//! argument per level); the control point P_i equals f(u_{i+1}, …, u_{i+p}) on any non-empty span
//! i ≤ span ≤ i + p.
Eigen::RowVector3d blossom(const BSplineCurve& c, int span, const std::vector<double>& args);

//! The same curve with the knot t inserted `times` times (Boehm); times is reduced so that the
//! multiplicity of t stays at most p. t must lie inside the domain (start < t < end); otherwise
//! the curve is returned unchanged.
BSplineCurve inserted_knot(const BSplineCurve& c, double t, int times = 1);

//! The same curve with every knot of `knots` inserted (a knot listed k times is inserted k times).
BSplineCurve refined(const BSplineCurve& c, const std::vector<double>& knots);

//! The same curve at degree ≥ c.degree, exactly: every distinct knot gains one multiplicity per
//! degree step and the new control points are averaged blossom values
//! Q_i = F(u′_{i+1}, …, u′_{i+p+1}), F(a_1..a_{p+1}) = Σ_k f(a without a_k)/(p + 1).
BSplineCurve degree_elevated(const BSplineCurve& c, int degree);

//! Greville abscissae ξ_i = (u_{i+1} + … + u_{i+p})/p, i = 0 … count − 1 (#count); they satisfy
//! Σ_i ξ_i N_{i,p}(t) = t (linear precision).
Eigen::VectorXd greville_abscissae(const BSplineCurve& c);

//! The same point set over the domain [a, b] (the knots mapped affinely; the points unchanged):
//! result(a + s(b − a)) = c(start + s(end − start)).
BSplineCurve reparametrised(const BSplineCurve& c, double a, double b);

//! The distinct knots of a knot vector and their multiplicities, in increasing order.
std::vector<std::pair<double, int>> knot_multiplicities(const Eigen::VectorXd& knots);

}  // namespace coons
