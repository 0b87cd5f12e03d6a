// Scaling by powers of two (internal to solvers/). The backends' stopping tests compare squared
// norms, which underflow for entries below about 1e-154 (‖b‖² = 0: "x = 0 is the answer") and
// overflow above about 1e+154. So the common solve path (linear_solver.cpp) hands a backend each
// right-hand-side column whose largest magnitude lies outside [2^−128, 2^128] (about 3e−39 to 3e+38)
// multiplied by a power of two that brings it into [1/2, 1), and multiplies X back; residuals are
// measured without underflow or overflow. Multiplying by a power of two is exact in floating
// point while no result is subnormal or infinite: the scaled system has exactly the scaled
// solution. Columns inside that range, and norms that neither underflow nor overflow, are left as
// they are (the same bits as before, and no extra pass over a large grid).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

namespace coons::solvers {

//! Columns whose largest magnitude is below 2^kSafeExponent and at least 2^−kSafeExponent are
//! solved as they are: their squared norms, times a tolerance², stay far from underflow and overflow.
constexpr int kSafeExponent = 128;

//! e with largest = m·2^e, m in [1/2, 1); 0 for zero, a NaN or an infinity.
inline int exponent_of(double largest) {
  if (!(largest > 0) || !std::isfinite(largest)) return 0;
  int e = 0;
  std::frexp(largest, &e);
  return e;
}

//! max|v|: NaN when v holds a NaN wherever it lies (plain maxCoeff drops one that is not first),
//! +inf for an infinity, 0 for an empty v.
inline double largest_abs(const Eigen::Ref<const Eigen::VectorXd>& v) {
  return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff<Eigen::PropagateNaN>();
}

//! e with max|v| = m·2^e, m in [1/2, 1); 0 for a zero vector or one with a NaN or infinity.
inline int magnitude_exponent(const Eigen::Ref<const Eigen::VectorXd>& v) { return exponent_of(largest_abs(v)); }

//! v ← v·2^e, entry by entry, exactly (rounded as std::ldexp rounds: only subnormal results lose bits).
inline void scale_by_power_of_two(Eigen::Ref<Eigen::VectorXd> v, int e) {
  if (e == 0) return;
  if (std::abs(e) <= 1022) {
    v *= std::ldexp(1.0, e);  // a normal power of two: each product is rounded once, as ldexp rounds
  } else {
    v = v.unaryExpr([e](double x) { return std::ldexp(x, e); });
  }
}

//! The exponents by which the common solve path scales the columns of a right-hand side B
//! (column k by 2^−e[k]): the magnitude exponent of a column outside [2^−kSafeExponent,
//! 2^kSafeExponent), 0 for the others (rhs_exponents: less for a column whose small entries
//! would underflow).
using ColumnExponents = std::array<int, 3>;

//! The exponent by which the common solve path scales a column whose largest magnitude is
//! `largest` (a NaN or an infinity: 0).
inline int scaling_exponent(double largest) {
  const int e = exponent_of(largest);
  return std::abs(e) > kSafeExponent ? e : 0;
}

//! e with smallest = m·2^e over the nonzero finite entries of v, m in [1/2, 1); 0 when none.
inline int smallest_nonzero_exponent(const Eigen::Ref<const Eigen::VectorXd>& v) {
  double smallest = HUGE_VAL;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (const double a = std::abs(v(i)); a > 0 && a < smallest) smallest = a;
  return smallest < HUGE_VAL ? exponent_of(smallest) : 0;
}

//! The scaling exponents of B's columns (scaling_exponent), except that a large column is scaled
//! down no further than its smallest nonzero entry allows (to about 2^−1000), while its largest
//! stays below about 2^500: B = (1e-200, 1e200) scaled to [1/2, 1) lost its 1e-200 to underflow,
//! and every backend returned x = (0, 1e200) for the identity.
inline ColumnExponents rhs_exponents(const Eigen::MatrixX3d& B) {
  ColumnExponents e{};
  for (int k = 0; k < 3; ++k) {
    int& ek = e[std::size_t(k)];
    ek = scaling_exponent(largest_abs(B.col(k)));
    if (ek <= 0) continue;  // scaling up cannot underflow
    const int smallest = smallest_nonzero_exponent(B.col(k));
    if (smallest - ek < -1000) ek = std::max(ek - 500, smallest + 1000);
  }
  return e;
}

inline bool is_identity(const ColumnExponents& e) { return e[0] == 0 && e[1] == 0 && e[2] == 0; }

//! M with column k multiplied by 2^(sign·e[k]) (sign −1: down to a largest magnitude in [1/2, 1);
//! +1: back up).
inline Eigen::MatrixX3d scaled_columns(Eigen::MatrixX3d M, const ColumnExponents& e, int sign) {
  for (int k = 0; k < 3; ++k) scale_by_power_of_two(M.col(k), sign * e[std::size_t(k)]);
  return M;
}

//! True when a sum of squares s of v is exact enough to take its root: finite, and either not
//! near underflow (then squares that did underflow are far below its rounding) or v is zero.
inline bool safe_sum_of_squares(double s, const Eigen::Ref<const Eigen::VectorXd>& v) {
  if (s >= 0x1p-900 && s <= 0x1p+1000) return true;  // (false for a NaN or an infinity)
  return s == 0 && v.isZero(0);
}

//! ‖r‖₂ / ‖b‖₂ (‖r‖₂ when b = 0) without underflow or overflow of the squares: r.norm() / b.norm()
//! (the same bits) when both sums of squares are safe, otherwise both norms taken on r and b scaled
//! by powers of two.
inline double relative_norm(const Eigen::Ref<const Eigen::VectorXd>& r, const Eigen::Ref<const Eigen::VectorXd>& b) {
  const double r2 = r.squaredNorm(), b2 = b.squaredNorm();
  if (safe_sum_of_squares(r2, r) && safe_sum_of_squares(b2, b)) {
    const double r_norm = std::sqrt(r2), b_norm = std::sqrt(b2);
    return b_norm > 0 ? r_norm / b_norm : r_norm;
  }
  const int er = magnitude_exponent(r), eb = magnitude_exponent(b);
  Eigen::VectorXd rs = r, bs = b;
  scale_by_power_of_two(rs, -er);
  scale_by_power_of_two(bs, -eb);
  const double r_norm = rs.norm(), b_norm = bs.norm();
  if (b_norm > 0) return std::ldexp(r_norm / b_norm, er - eb);
  return std::ldexp(r_norm, er);
}

//! max over the columns of relative_norm(R.col(c), B.col(c)): the relative residual of both
//! residual functions (LinearSolver's and bench-matrix's); NaN when any column gives NaN (which
//! std::max would drop).
inline double max_relative_norm(const Eigen::Ref<const Eigen::MatrixXd>& R,
                                const Eigen::Ref<const Eigen::MatrixXd>& B) {
  double worst = 0;
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    const double q = relative_norm(R.col(c), B.col(c));
    if (std::isnan(q)) return q;
    worst = std::max(worst, q);
  }
  return worst;
}

}  // namespace coons::solvers
