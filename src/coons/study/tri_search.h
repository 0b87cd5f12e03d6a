// The search for the best member c of the triangular mask family (tri_mask.h) of one boundary for
// an objective: exact energies of tri_energy.h (thin_plate, dirichlet, twist, e3), their discrete forms
// (discrete_thin_plate, discrete_dirichlet, discrete_twist), the mean squared distance to an analytic
// target (target: sphere, cylinder or plane of the boundary file), or weighted sums of them
// ("thin_plate+10*target"). Each evaluation solves A(c) X = B(c) once and, for the derivative, once
// more with the same factorisation: A·∂X/∂c = tri_mask_sensitivity_rhs (one extra solve); the energies
// are quadratic forms Q, so dQ(P)/dc = [Q(P + s·∂P) − Q(P − s·∂P)]/(2s) exactly (polarisation, any
// s > 0), and the target term is differentiated by the chain rule through the sampled surface.
// The search scans a grid (a singular member is a failed point, skipped unless the verdict rests
// on it), reports a flat objective (range at the objective's rounding floor) or an optimum on a
// bound (the derivative points outward) as such, and refines the best scan point downhill inside
// the bracket of its neighbours by secant steps on f′ = 0 and bisections, to a vanishing slope.
// Default bounds: [−1/6 − 1/(4(n−3)), 1/3] (n ≥ 4; for n = 3 the n = 4 value −5/12):
// halfway between the singular member c*ₙ = −1/6 − 1/(2(n−3)) and the quadratic-precision member
// −1/6, up to 1/3; no member in (c*ₙ, 1/3] is singular for n = 4 … 20 (tests/tri/tri_solve_test.cpp).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/tri/tri_net.h"
#include "coons/tri/tri_solve.h"

namespace coons {

enum class TriTerm {
  kThinPlate,
  kDirichlet,
  kTwist,
  kE3,
  kDiscreteThinPlate,
  kDiscreteDirichlet,
  kDiscreteTwist,
  kTarget
};

struct TriObjective {
  std::string name;                               //!< as given (spaces removed)
  std::vector<std::pair<TriTerm, double>> terms;  //!< Σ weight·term
  std::optional<Target> target;                   //!< sphere, cylinder or plane (kTarget terms)
  [[nodiscard]] bool uses_target() const;
};

//! "thin_plate", "dirichlet+0.5*twist", "2*target+thin_plate"; nullopt (and why) for anything else.
std::optional<TriObjective> parse_tri_objective(const std::string& text, std::string* why);

//! The default search bounds for degree n (above).
std::pair<double, double> default_tri_bounds(int n);

//! Mean squared distance of the surface sampled with target.samples points per side to the target.
double tri_target_mean_square(const tri::TriNet& net, const Target& target);

//! The objective of a net (no derivative).
double tri_objective_value(const tri::TriNet& net, const TriObjective& objective);

struct TriEvaluation {
  double parameter = 0, value = 0, derivative = 0;
  bool has_derivative = false;
  solvers::SolveSummary summary;
  tri::TriNet net;
  [[nodiscard]] bool ok() const { return summary.ok(); }
};

//! Solves the system of c (and its sensitivity when `with_derivative`) and evaluates the objective.
TriEvaluation evaluate_tri_objective(const tri::TriNet& frame, const TriObjective& objective, double c,
                                     const solvers::SolverInfo& solver, bool with_derivative);

//! The search over c in [options.lower, options.upper] (AlphaSearchOptions: bounds, scan points,
//! tolerances); the summary's parameter is c.
AlphaSearchSummary search_tri_c(const tri::TriNet& frame, const TriObjective& objective,
                                const solvers::SolverInfo& solver, const AlphaSearchOptions& options);

}  // namespace coons
