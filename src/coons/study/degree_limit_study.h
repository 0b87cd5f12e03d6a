// The measured degree law of one shape and objective: α* and μ* at every degree (the boundary
// refitted from its analytic sides or elevated exactly, as in the study), the limit μ∞ of μ*(n)
// with its error, rate and fits (degree_limit.h), the continuum optimum μ_c by the Ritz method at
// several degrees N (continuum_limit.h, independent of the masks), and two other
// parametrisations whose optima are compared with μ* for their spread over the degrees:
// μ_exact(n), the exact-energy mask parameter of the α*-net (exact_energy_mu), and ν*(n), the
// optimum of the exact-energy (Galerkin) family at degree n itself. μ = −n²(1 + 4α)/(4α)
// (docs/math.md §4) maps α* ∈ (−1/4, 0) to μ*; α* ≥ 0 has no μ (reported as on the bound).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/study/continuum_limit.h"
#include "coons/study/degree_limit.h"
#include "coons/study/study.h"

namespace coons {

struct DegreeLimitStudyOptions {
  std::vector<int> degrees;                           //!< increasing, each in [2, 200]
  std::vector<int> continuum_degrees = {24, 32, 40};  //!< N of the Ritz spaces, increasing
  int spread_from = 4, spread_to = 32;                //!< degrees over which spreads are taken
  int exact_mu_max_degree = 32;                       //!< μ_exact and ν* up to this degree
  const solvers::SolverInfo* solver = nullptr;        //!< nullptr: auto; else one check_search_backend accepts
  DegreeLimitOptions limit;
  ContinuumOptions continuum;

  bool is_valid(std::string* why) const;
};

//! α ↦ μ for m = n: −n²(1 + 4α)/(4α); nullopt unless −1/4 < α < −kAlphaZeroWithinRounding (sweep.h).
std::optional<double> mu_of_alpha(int n, double alpha);

enum class DegreeOptimum { kInterior, kFlat, kAtBound, kFailed };
const char* to_string(DegreeOptimum kind);  //!< "interior", "flat", "at_bound", "failed"

struct DegreeLimitCell {
  int degree = 0;
  DegreeOptimum kind = DegreeOptimum::kInterior;
  AlphaSearchSummary alpha;
  std::optional<double> mu;                  //!< μ* (interior α* < 0 only)
  std::optional<double> exact_mu;            //!< μ_exact of the α*-net (degree ≤ exact_mu_max_degree)
  std::optional<ContinuumOptimum> galerkin;  //!< ν*: the exact-energy family at this degree
  std::optional<double> max_deviation;       //!< refitted sides: their largest deviation
};

struct Spread {  //!< max/min of a parametrisation's optimum over [spread_from, spread_to]
  std::optional<double> ratio;
  int points = 0;
  int from = 0, to = 0;  //!< the smallest and largest degree that counted (0 without points)
};

struct DegreeLimitEntry {
  std::string boundary, objective;
  std::vector<DegreeLimitCell> cells;
  DegreeLimitResult limit;                           //!< of the interior μ*(n)
  std::vector<ContinuumOptimum> continuum;           //!< one per continuum degree
  std::optional<std::string> continuum_unavailable;  //!< why (objective not a sum of exact energies)
  //! Degrees asked for (--degrees, --continuum-degrees) that the shape does not have: below its
  //! own degree with no analytic curves to refit from (elevation only raises); `skipped_reason` why.
  std::vector<int> skipped_degrees, skipped_continuum_degrees;
  std::optional<std::string> skipped_reason;
  Spread mu_spread, exact_mu_spread, galerkin_spread;
};

//! The degrees of `degrees` that `input` cannot be studied at: below its own degree in u or v when
//! it has no analytic curves to refit from (degree elevation only raises); in their order.
std::vector<int> unreachable_degrees(const StudyInput& input, const std::vector<int>& degrees);
//! Why they cannot (the sentence of DegreeLimitEntry::skipped_reason).
std::string unreachable_reason(const StudyInput& input);

//! One shape and objective. A refit that fails is an input error, thrown before any search. The
//! degrees of unreachable_degrees are skipped; when that is every one of options.degrees the entry
//! has no cells (the CLI refuses such a request before it runs).
DegreeLimitEntry run_degree_limit(const StudyInput& input, const Objective& objective,
                                  const DegreeLimitStudyOptions& options);

//! The continuum optimum at the largest N with a success, and its change from the N before.
struct ContinuumSummary {
  std::optional<double> mu, change;
  int degree = 0;
};
ContinuumSummary continuum_summary(const DegreeLimitEntry& entry);

//! The fields of `coons degree-limit` (docs/formats.md): degrees, alpha_star, mu_star, mu_limit, ...
nlohmann::json degree_limit_json(const DegreeLimitEntry& entry);

}  // namespace coons
