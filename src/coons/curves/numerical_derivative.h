// Derivatives of a vector function of one variable by finite differences with Richardson
// extrapolation (Ridders' tableau): the step shrinks by 1.4 per row, each column removes the next
// error term, and the entry whose two neighbours agree best is returned with that disagreement as
// its error estimate. A first step too large for the function's scale can give a confident but
// wrong tableau, so the tableau is repeated from a 4× smaller first step until two agree (to 1e-7
// relative; at most eight starts, 0.1 … 0.1/4⁷, so that detail down to about 1e-3 of the
// parameter, as in sin(1000 s), is resolved; an agreeing pair after the fourth start counts only
// near the fourth's value, within its error estimate; when none agree, the fourth, 0.1/64, as
// before, with its disagreement with the third folded in).
// Based on: C. J. F. Ridders, Accurate computation of F'(x) and F'(x)F''(x), Adv. Eng. Software 4
// (1982) 75–76; W. H. Press et al., Numerical Recipes, 3rd ed. (2007), §5.7 (dfridr).
//
// Accuracy (measured on sin ωs, cos ωs, exp s with ω up to 50, and checked in
// tests/curves/analytic_curve_test.cpp): relative to the size of the derivative, ≈ 1e-13 for
// order 1, ≈ 1e-12 for order 2, ≈ 1e-10 for order 3. Central differences are used (even error
// expansion in h); when they hit a non-finite value (the function is undefined just outside its
// domain, e.g. sqrt at 0) or disagree with differences inside the domain (a function that is another
// one outside it, such as |sin πs| on [0, 1]) the step is first limited to the room left inside the domain, and at the
// domain's ends one-sided differences pointing into it are used, which are less accurate (≈ 1e-8
// for order 1).
#pragma once

#include <Eigen/Core>
#include <functional>

namespace coons {

struct NumericalDerivative {
  Eigen::RowVector3d value = Eigen::RowVector3d::Zero();
  double error_estimate = 0;  //!< max-norm disagreement of the last two extrapolations
  bool one_sided = false;     //!< central differences were impossible (non-finite samples)
  //! What rounding of the function's values alone makes of the returned entry: ε·max|f| over the
  //! samples, times the difference's weights over h^r, times 3 per extrapolation column. A
  //! function far from the origin (a curve at x = 1e8) has an error estimate of this size however
  //! smooth it is; a singular derivative has one far above it.
  double rounding = 0;
  double step = 0;  //!< h of the returned entry's row
  int column = 0;   //!< its extrapolation column
};

//! d^r f / ds^r at s, r = 1, 2 or 3, starting from step h0 (default 0.1).
//! [domain_lo, domain_hi] is where f is the function meant: where the first steps leave it, an
//! estimate from differences inside it (central from the room left, else one-sided) is made too,
//! and replaces the central one unless they agree to its accuracy (|sin πs| at 0 gives π, not 0).
NumericalDerivative numerical_derivative(const std::function<Eigen::RowVector3d(double)>& f, int r, double s,
                                         double h0 = 0, double domain_lo = 0, double domain_hi = 1);

}  // namespace coons
