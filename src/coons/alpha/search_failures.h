// No optimum without its evidence: what a search does with the evaluations that failed. Every
// evaluation is logged as (parameter, succeeded); the failed ones are counted and grouped into
// runs (intervals with no success between them), and a verdict that rests on one of them — an
// optimum whose scan bracket holds a failure, or a flat objective with any — becomes
// SearchStatus::kFailedRegion, with no parameter. Sizes: the log, one entry per evaluation.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "coons/alpha/alpha_search.h"

namespace coons::detail {

//! [lowest, highest] parameter of each run of failed evaluations, ascending.
std::vector<std::pair<double, double>> failed_runs(std::vector<std::pair<double, bool>> log);

//! Fills failed_evaluations and failed_intervals of s from the log and, where the verdict rests
//! on a failure, turns it into kFailedRegion (the message says where and why).
void judge_failures(AlphaSearchSummary& s, const std::vector<std::pair<double, bool>>& log);

//! The same, with the optimum's evidence taken from `evidence` (parameter, value), the scan its
//! search ran on, in place of s.scan: a search between poles judges its optimum by its own
//! interval's scan, not by a neighbour across a pole, where refused evaluations sit.
void judge_failures(AlphaSearchSummary& s, const std::vector<std::pair<double, bool>>& log,
                    const std::vector<std::pair<double, double>>& evidence);

}  // namespace coons::detail
