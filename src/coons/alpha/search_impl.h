// Internal to the one-parameter mask searches (alpha_search.cpp, family_search.cpp): their entry
// point and the search over bounds that hold poles.
//   search_impl       the search in the evaluator's normalised frame (InUnitFrame, search_run.h),
//                     values back in the caller's units, failures judged (search_failures.h): one
//                     SearchRun over the bounds, or search_intervals where they hold poles;
//   search_intervals  one SearchRun per interval between poles and per margin beside each pole,
//                     the lowest result kept, with the scan its optimum rests on.
// Sizes: every scan (at least 5 points per interval and per margin searched) and the log.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/search_failures.h"
#include "coons/alpha/search_run.h"
#include "solvers/linear_solver.h"

namespace coons::detail {

//! A search between poles and the scan its optimum rests on, for judge_failures: that
//! interval's own (the lowest point of all the scans joined may lie in another interval, beside
//! another pole's refused evaluations).
struct IntervalSearch {
  AlphaSearchSummary summary;
  std::vector<std::pair<double, double>> evidence;
};

//! The most singular parameters inside the bounds for which each interval between them is
//! searched on its own (search_intervals); beyond it one search spans them.
inline constexpr std::size_t kMaxSingularIntervals = 64;
//! Searches of the margin beside a pole, each 16 times closer to it (search_intervals).
inline constexpr int kMarginSearches = 8;

// Bounds that hold singular parameters (--allow-indefinite): at each the net, and so the
// objective, has a pole and rises to +∞ on both sides, so every interval between two of them holds
// a minimum of its own, which one scan across the poles sees only when a scan point falls into
// it (a random 5 × 3 boundary over [−1, 1]: scan points 0.25 apart, a pole at 0.39, and the
// minimum 13.324 at 0.314 was missed for 13.377 at 0.493). So each interval is searched on its
// own, from half a scan cell off each pole, and the lowest result kept. A minimum can also lie in
// that margin, behind a rise where no slope points to it (t8x8_10, thin_plate over [−1, 1]:
// 108.729 there, 111.705 inside): each margin is searched on its own (5 points, from a sixteenth
// of it off the pole), and again 16 times closer while the objective falls towards the pole, up
// to kMarginSearches searches in all.
template <class Obj>
IntervalSearch search_intervals(Obj& objective, const AlphaSearchOptions& options,
                                const std::vector<double>& singular) {
  std::vector<double> ends = {options.lower};
  ends.insert(ends.end(), singular.begin(), singular.end());
  ends.push_back(options.upper);
  const std::size_t intervals = ends.size() - 1;
  const auto start = std::chrono::steady_clock::now();
  std::vector<AlphaSearchSummary> results;
  std::vector<std::pair<double, double>> scan;  // every scan point of every search, ascending at the end
  int local_minima = 0;
  std::vector<std::string> unfinished;  // pole sides whose minimum no search reached
  const auto has_optimum = [](const AlphaSearchSummary& r) {
    return r.parameter && (r.status == SearchStatus::kSuccess || r.status == SearchStatus::kNotConverged);
  };
  const auto run = [&](double lower, double upper, int points) {
    AlphaSearchOptions sub = options;
    sub.scan_points = points;
    sub.lower = lower;
    sub.upper = upper;
    AlphaSearchSummary r = SearchRun<Obj>(objective, sub).run();
    scan.insert(scan.end(), r.scan.begin(), r.scan.end());
    local_minima += r.local_minima;
    return r;
  };
  // An interval's share of the scan: its width, or on bounds scanned in asinh (scan_point) its
  // width there.
  const bool wide = options.upper - options.lower > kWideScanWidth;
  const auto measure = [wide](double a, double b) {
    return wide ? std::asinh(b / kWideScanScale) - std::asinh(a / kWideScanScale) : b - a;
  };
  for (std::size_t i = 0; i < intervals; ++i) {
    const double width = ends[i + 1] - ends[i];
    // the scan's points shared out by width (at least 5 each; each margin searched adds 5)
    const int points = std::clamp(
        int(std::lround(options.scan_points * measure(ends[i], ends[i + 1]) / measure(options.lower, options.upper))),
        5, std::max(options.scan_points, 5));
    // half a scan cell off each pole: the first and last cell of the interval's own scan, and on
    // a wide interval at most the half cell of one kWideScanWidth wide (its asinh cells next to a
    // pole far from 0 span millions on [−1e60, 1e60]; the margin searches go 16 times closer each)
    const int half_cells = 2 * (points - 1) + 1;
    const double margin = width / (2 * (points - 1)), natural = kWideScanWidth / (2 * (points - 1));
    const double margin_below = width > kWideScanWidth
                                    ? std::min(scan_point(ends[i], ends[i + 1], half_cells, 1) - ends[i], natural)
                                    : margin,
                 margin_above =
                     width > kWideScanWidth
                         ? std::min(ends[i + 1] - scan_point(ends[i], ends[i + 1], half_cells, half_cells - 2), natural)
                         : margin;
    const double lower = i > 0 ? ends[i] + margin_below : ends[i],
                 upper = i + 1 < intervals ? ends[i + 1] - margin_above : ends[i + 1];
    if (!(lower < upper)) {  // (poles closer than rounding lets the margins apart)
      results.emplace_back().status = SearchStatus::kSolverFailed;
      results.back().message = "the interval between two poles is narrower than its margins";
      continue;
    }
    AlphaSearchSummary r = run(lower, upper, points);
    for (const int side : {-1, 1}) {  // the pole below (−1), then the pole above (+1)
      if ((side < 0 && i == 0) || (side > 0 && i + 1 == intervals)) continue;
      const double pole = side < 0 ? ends[i] : ends[i + 1];
      // The slope towards the pole: it falls where f' has the sign opposite the side's.
      enum class Slope { kFalls, kRises, kFailed };
      const auto slope_at = [&](double p) {
        const auto e = objective.evaluate(p);
        if (!e.ok()) return Slope::kFailed;
        return -side * e.derivative > e.derivative_noise ? Slope::kFalls : Slope::kRises;
      };
      double near = side < 0 ? lower : upper, gap = side < 0 ? margin_below : margin_above;
      double solved = near;  // the scan point closest to the pole whose evaluation succeeded
      bool rose = false;     // a search stopped where the objective rises towards the pole
      for (int level = 0; level < kMarginSearches; ++level, gap /= 16) {
        if (level > 0) {
          const Slope slope = slope_at(near);
          if (slope != Slope::kFalls) {
            rose = slope == Slope::kRises;
            break;
          }
        }
        const double closer = pole - side * gap / 16;
        if (!(side < 0 ? closer < near : near < closer)) break;
        AlphaSearchSummary g = side < 0 ? run(closer, near, 5) : run(near, closer, 5);
        for (const auto& [p, value] : g.scan)
          if (std::isfinite(value) && std::abs(p - pole) < std::abs(solved - pole)) solved = p;
        if (has_optimum(g) && (!has_optimum(r) || g.value < r.value)) r = std::move(g);
        near = closer;
      }
      // Where the objective still falls towards the pole at the closest point solved (the searches
      // stop at margin/16⁸ off it, and at evaluations refused next to it), a minimum lies between
      // them that no search reached: whatever the lowest result is, it may not be the minimum.
      if (!rose && slope_at(solved) == Slope::kFalls)
        unfinished.push_back("the objective still falls towards the pole at " + solvers::format_g(pole) +
                             " at the closest point solved, " + solvers::format_g(solved) + " (" +
                             solvers::format_g(std::abs(pole - solved)) +
                             " from it): a minimum lies between them that no search reached");
    }
    results.push_back(std::move(r));
  }
  // the lowest optimum; else (none found) the first interval's verdict
  std::size_t best = intervals;
  for (std::size_t i = 0; i < intervals; ++i)
    if (has_optimum(results[i]) && (best == intervals || results[i].value < results[best].value)) best = i;
  // no optimum: flat where every interval is flat or could not be solved at all, else the first
  // interval's verdict that is neither
  std::size_t shown = best;
  if (best == intervals) {
    shown = 0;
    const auto flat_or_failed = [](const AlphaSearchSummary& r) {
      return r.flat || r.status == SearchStatus::kSolverFailed;
    };
    const bool flat = std::all_of(results.begin(), results.end(), flat_or_failed) &&
                      std::any_of(results.begin(), results.end(), [](const AlphaSearchSummary& r) { return r.flat; });
    for (std::size_t i = 0; i < intervals; ++i)
      if (flat ? results[i].flat : !flat_or_failed(results[i])) {
        shown = i;
        break;
      }
  }
  IntervalSearch found{std::move(results[shown]), {}};
  AlphaSearchSummary& s = found.summary;
  found.evidence = std::move(s.scan);   // the optimum's own interval's scan
  std::sort(scan.begin(), scan.end());  // (a margin's scan ends on its interval's first point: once)
  scan.erase(std::unique(scan.begin(), scan.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
             scan.end());
  s.scan = std::move(scan);
  s.local_minima = local_minima;
  // on a bound of the search only where the bound is one of the caller's
  s.at_bound = s.parameter && lies_on_bound(*s.parameter, options.lower, options.upper);
  std::string note = "the bounds hold " + std::to_string(singular.size()) + " singular parameter" +
                     (singular.size() == 1 ? "" : "s") + " (poles of the objective); each of the " +
                     std::to_string(intervals) + " intervals between them was searched on its own";
  if (best != intervals) note += " and the lowest result kept";
  s.message = note + (s.message.empty() ? "" : "; " + s.message);
  if (best != intervals && !unfinished.empty()) {  // a lower minimum may lie where no search went
    if (s.status == SearchStatus::kSuccess) s.status = SearchStatus::kNotConverged;
    for (const std::string& text : unfinished) s.message += "; " + text;
  }
  s.evaluations = objective.evaluations();
  s.solves = objective.solves();
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return found;
}

// The search in the evaluator's normalised frame, its values reported in the caller's units.
template <class Obj>
AlphaSearchSummary search_impl(Obj& objective, const AlphaSearchOptions& options) {
  InUnitFrame<Obj> unit(objective);
  const std::vector<double> singular = unit.singular_parameters(options.lower, options.upper);
  IntervalSearch found = singular.empty() || singular.size() > kMaxSingularIntervals
                             ? IntervalSearch{search_in_frame(unit, options), {}}
                             : search_intervals(unit, options, singular);
  AlphaSearchSummary& s = found.summary;
  if (singular.size() > kMaxSingularIntervals)
    s.message += std::string(s.message.empty() ? "" : "; ") + "the bounds hold " + std::to_string(singular.size()) +
                 " singular parameters, more than the " + std::to_string(kMaxSingularIntervals) +
                 " whose intervals are searched one by one: minima between scan points may be missed";
  s.value *= unit.value_factor();
  for (auto& point : s.scan) point.second *= unit.value_factor();
  s.first_failure = unit.first_failure();
  judge_failures(s, unit.log(), found.evidence.empty() ? s.scan : found.evidence);
  return std::move(found.summary);
}

}  // namespace coons::detail
