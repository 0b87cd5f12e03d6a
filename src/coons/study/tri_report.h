// The reports of triangular boundaries (docs/formats.md, "Triangular boundaries"): the solve
// report ("type": "triangle", degree, method, alpha = c and a, the solver block, the net in the
// contract's row order, the metrics of tri_energy.h), the search report over c, and one line of a
// sweep over c.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "coons/alpha/alpha_search.h"
#include "coons/study/tri_search.h"
#include "coons/tri/tri_energy.h"
#include "coons/tri/tri_solve.h"

namespace coons {

nlohmann::json tri_metrics_to_json(const tri::TriNetMetrics& metrics);

//! The solve report without the timing block; net and metrics null when the solve failed.
nlohmann::json tri_solve_report(const tri::TriBoundary& boundary, const tri::TriMask& mask,
                                const tri::TriSolveResult& result, bool solver_picked_automatically);

//! The search report over c (alpha = c*, a = (1 − 3c*)/6, null when flat or failed).
nlohmann::json tri_search_report(const tri::TriBoundary& boundary, const std::string& objective,
                                 const AlphaSearchOptions& options, const AlphaSearchSummary& s);

//! One JSON Lines record of a sweep over c: c, a, status, every metric, rms_target with a target.
nlohmann::json tri_sweep_line(const tri::TriBoundary& boundary, const TriEvaluation& e,
                              const TriObjective& target_only);

}  // namespace coons
