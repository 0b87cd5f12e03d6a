// The report of a mask-parameter search (docs/formats.md, `coons search-alpha`): the optimum in
// α, β and μ, the value, bounds, flat / at_bound, the scan and the solver block.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "coons/alpha/alpha_search.h"
#include "coons/mask/mask_families.h"
#include "coons/net/control_net.h"
#include "solvers/registry.h"

namespace coons {

//! What a search varies: α of the Farin–Hansford family, μ of the anisotropic masks (searched
//! on the compressed scale μ/(μ + mn)), (α, γ), every symmetric affine-invariant 3×3 mask, or the
//! weight w of the 5×5 C1 family (family_search.h).
enum class SearchParameter { kAlpha, kMu, kAlphaGamma, kWeight };
const char* to_string(SearchParameter parameter);

//! The solver block of a search report, of the same shape as a solve's: the backend, the
//! search's verdict, its solves as iterations (no residual: many systems are solved).
nlohmann::json search_solver_block(const solvers::SolverInfo& solver, bool picked_automatically, SearchStatus status,
                                   int solves, double seconds, const std::string& message);

//! The fields every one-parameter report shares, from "flat" to "first_failure": verdict, counts,
//! scan, evaluator (`evaluator_when_unnamed` where the summary names none) and the failed
//! evaluations; `shown` maps a searched parameter to the units of the report.
void add_search_fields(nlohmann::json& out, const AlphaSearchSummary& s, const std::function<double(double)>& shown,
                       const std::string& evaluator_when_unnamed = "factorize and solve");

//! The report of a one-parameter search (α or μ; `family` maps the searched parameter to its
//! mask, `options` holds the bounds it was searched in). A μ search reports μ and its bounds on
//! `mu_scale` (default: the μ of options' compressed bounds), every μ within them.
nlohmann::json search_report(const Boundary& boundary, const std::string& objective, SearchParameter parameter,
                             const MaskFamily& family, const AlphaSearchOptions& options, const AlphaSearchSummary& s,
                             const std::optional<MuScale>& mu_scale = std::nullopt);

//! The report of the C1 family's weight search: "parameter": "weight", "mask": "c1-family",
//! "weight" (w*, null without an optimum) and the fields of the α report other than alpha, beta, mu.
nlohmann::json weight_search_report(const Boundary& boundary, const std::string& objective,
                                    const AlphaSearchOptions& options, const AlphaSearchSummary& s);

//! The report of the (α, γ) search.
nlohmann::json alpha_gamma_report(const Boundary& boundary, const std::string& objective,
                                  const AlphaSearchOptions& options, const AlphaGammaSummary& g);

}  // namespace coons
