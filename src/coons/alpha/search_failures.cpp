#include "search_failures.h"

#include <algorithm>
#include <cmath>

#include "solvers/linear_solver.h"

namespace coons::detail {

// Runs of failed evaluations, as [lowest, highest] parameter with no success between them.
std::vector<std::pair<double, double>> failed_runs(std::vector<std::pair<double, bool>> log) {
  std::sort(log.begin(), log.end());
  std::vector<std::pair<double, double>> runs;
  bool open = false;
  for (const auto& [p, ok] : log) {
    if (ok) {
      open = false;
    } else if (open) {
      runs.back().second = p;
    } else {
      runs.emplace_back(p, p);
      open = true;
    }
  }
  return runs;
}

namespace {

std::string describe(const std::vector<std::pair<double, double>>& runs) {
  constexpr std::size_t kShown = 4;
  std::string text;
  for (std::size_t r = 0; r < runs.size() && r < kShown; ++r) {
    const auto [lo, hi] = runs[r];
    if (!text.empty()) text += ", ";
    text += lo == hi ? solvers::format_g(lo) : "[" + solvers::format_g(lo) + ", " + solvers::format_g(hi) + "]";
  }
  if (runs.size() > kShown) text += " and " + std::to_string(runs.size() - kShown) + " more places";
  return text;
}

}  // namespace

// No optimum without its evidence: the optimum rests on the best successful scan point and its two
// scan neighbours (the refinement stays between them); a flat verdict rests on every scan point.
// Where a failed evaluation lies among them, nothing is claimed (kFailedRegion).
void judge_failures(AlphaSearchSummary& s, const std::vector<std::pair<double, bool>>& log) {
  judge_failures(s, log, s.scan);  // (it changes no scan)
}

void judge_failures(AlphaSearchSummary& s, const std::vector<std::pair<double, bool>>& log,
                    const std::vector<std::pair<double, double>>& evidence) {
  const std::vector<std::pair<double, double>> runs = failed_runs(log);
  s.failed_intervals = runs;
  s.failed_evaluations = int(std::count_if(log.begin(), log.end(), [](const auto& e) { return !e.second; }));
  if (s.failed_evaluations == 0 || s.status == SearchStatus::kSolverFailed) return;
  const std::string where = std::to_string(s.failed_evaluations) + " evaluation(s) failed at " + describe(runs);
  auto append = [&](const std::string& text) { s.message += (s.message.empty() ? "" : "; ") + text; };
  if (s.flat) {
    s.status = SearchStatus::kFailedRegion;
    s.flat = false;
    append(where + ": the successful ones are flat, but that does not make the objective flat over the bounds");
    return;
  }
  if (!s.parameter) return;
  int best = -1;
  for (int i = 0; i < int(evidence.size()); ++i)
    if (std::isfinite(evidence[i].second) && (best < 0 || evidence[i].second < evidence[best].second)) best = i;
  if (best < 0) return;
  const double lo = evidence[std::max(best - 1, 0)].first;
  const double hi = evidence[std::min(best + 1, int(evidence.size()) - 1)].first;
  const bool touches = std::any_of(log.begin(), log.end(), [&](const auto& e) {
    return !e.second && e.first >= std::min(lo, *s.parameter) && e.first <= std::max(hi, *s.parameter);
  });
  if (!touches) {
    append(where + ", away from the optimum");
    return;
  }
  append(where + ": the lowest successful value, " + solvers::format_g(s.value) + " at " +
         solvers::format_g(*s.parameter) + ", lies next to them, so no optimum is claimed");
  s.status = SearchStatus::kFailedRegion;
  s.parameter.reset();
  s.at_bound = false;
}

}  // namespace coons::detail
