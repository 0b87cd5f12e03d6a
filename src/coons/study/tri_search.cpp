#include "coons/study/tri_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "coons/alpha/downhill.h"
#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/search_failures.h"
#include "coons/tri/tri_energy.h"
#include "coons/tri/tri_mask.h"
#include "coons/tri/tri_sampling.h"

namespace coons {

using tri::TriNet;

bool TriObjective::uses_target() const {
  return std::any_of(terms.begin(), terms.end(), [](const auto& t) { return t.first == TriTerm::kTarget; });
}

std::optional<TriObjective> parse_tri_objective(const std::string& text, std::string* why) {
  static const std::map<std::string, TriTerm> names = {{"thin_plate", TriTerm::kThinPlate},
                                                       {"dirichlet", TriTerm::kDirichlet},
                                                       {"twist", TriTerm::kTwist},
                                                       {"e3", TriTerm::kE3},
                                                       {"discrete_thin_plate", TriTerm::kDiscreteThinPlate},
                                                       {"discrete_dirichlet", TriTerm::kDiscreteDirichlet},
                                                       {"discrete_twist", TriTerm::kDiscreteTwist},
                                                       {"target", TriTerm::kTarget}};
  auto fail = [&](const std::string& reason) -> std::optional<TriObjective> {
    if (why) *why = reason;
    return std::nullopt;
  };
  TriObjective out;
  out.name = text;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t plus = std::min(text.find('+', start), text.size());
    std::string term = text.substr(start, plus - start);
    double weight = 1;
    if (const size_t star = term.find('*'); star != std::string::npos) {
      const std::string w = term.substr(0, star);
      char* end = nullptr;
      weight = std::strtod(w.c_str(), &end);
      if (w.empty() || end != w.c_str() + w.size() || !std::isfinite(weight) || weight <= 0)
        return fail("'" + w + "' is not a positive weight");
      term = term.substr(star + 1);
    }
    const auto it = names.find(term);
    if (it == names.end())
      return fail("unknown objective '" + term +
                  "' for a triangle (thin_plate, dirichlet, twist, e3, discrete_thin_plate, discrete_dirichlet, "
                  "discrete_twist, target, or a weighted sum such as thin_plate+10*target)");
    out.terms.emplace_back(it->second, weight);
    start = plus + 1;
  }
  return out;
}

std::pair<double, double> default_tri_bounds(int n) { return {-1.0 / 6 - 1.0 / (4.0 * std::max(n - 3, 1)), 1.0 / 3}; }

double tri_target_mean_square(const TriNet& net, const Target& target) {
  const int k = std::max(target.samples, 2);
  double sum = 0;
  int count = 0;
  for (int r = 0; r < k; ++r)
    for (int s = 0; s + r < k; ++s, ++count) {
      const double d = target_distance(target, tri::evaluate(net, tri::tri_sample_uvw(k, r, s)));
      sum += d * d;
    }
  return sum / count;
}

namespace {

double term_value(const TriNet& net, TriTerm term, const std::optional<Target>& target) {
  switch (term) {
    case TriTerm::kThinPlate:
      return tri::tri_thin_plate_energy(net);
    case TriTerm::kDirichlet:
      return tri::tri_dirichlet_energy(net);
    case TriTerm::kTwist:
      return tri::tri_twist_energy(net);
    case TriTerm::kE3:
      return tri::tri_e3_energy(net);
    case TriTerm::kDiscreteThinPlate:
      return tri::tri_discrete_thin_plate_energy(net);
    case TriTerm::kDiscreteDirichlet:
      return tri::tri_discrete_dirichlet_energy(net);
    case TriTerm::kDiscreteTwist:
      return tri::tri_discrete_twist_energy(net);
    case TriTerm::kTarget:
      return target ? tri_target_mean_square(net, *target) : 0.0;
  }
  return 0;
}

// d/dc of the mean squared distance: mean of 2·d·∇d·∂p/∂c over the samples (∂p: the surface of dnet).
double target_derivative(const TriNet& net, const TriNet& dnet, const Target& target) {
  const int k = std::max(target.samples, 2);
  double sum = 0;
  int count = 0;
  for (int r = 0; r < k; ++r)
    for (int s = 0; s + r < k; ++s, ++count) {
      const Eigen::Vector3d uvw = tri::tri_sample_uvw(k, r, s);
      Eigen::RowVector3d gradient;
      const double d = target_distance(target, tri::evaluate(net, uvw), &gradient);
      sum += 2 * d * gradient.dot(tri::evaluate(dnet, uvw));
    }
  return sum / count;
}

// Q(P + s·dP) − Q(P − s·dP) = 4s·B(P, dP) for a quadratic form Q, so dQ/dc = 2B(P, dP).
double quadratic_derivative(const TriNet& net, const TriNet& dnet, TriTerm term) {
  // the size of P about its centroid: the energies do not see a translation, so neither should s
  const double size = (net.points.rowwise() - net.points.colwise().mean()).norm(), dsize = dnet.points.norm();
  if (dsize == 0) return 0;
  const double s = size > 0 ? size / dsize : 1.0;
  TriNet plus = net, minus = net;
  plus.points += s * dnet.points;
  minus.points -= s * dnet.points;
  return (term_value(plus, term, std::nullopt) - term_value(minus, term, std::nullopt)) / (2 * s);
}

}  // namespace

double tri_objective_value(const TriNet& net, const TriObjective& objective) {
  double value = 0;
  for (const auto& [term, weight] : objective.terms) value += weight * term_value(net, term, objective.target);
  return value;
}

TriEvaluation evaluate_tri_objective(const TriNet& frame, const TriObjective& given, double c,
                                     const solvers::SolverInfo& solver, bool with_derivative) {
  TriEvaluation e;
  e.parameter = c;
  e.net = frame;
  // Solved and measured about the boundary's centre (tri::boundary_centre), the target moved with
  // it: every objective is invariant under translation, and far from the origin the rounding of
  // the coordinates made the search call a boundary moved by 2^47 flat.
  const Eigen::RowVector3d centre = tri::boundary_centre(frame);
  TriNet centred = frame;
  centred.points.rowwise() -= centre;
  TriObjective objective = given;
  if (objective.target) {
    objective.target->point -= centre;
    objective.target->net.points.rowwise() -= centre;
  }
  const tri::TriMask mask{c};
  const tri::TriBackendCheck check = tri::check_tri_backend(solver, mask);
  e.summary.solver = solver.name;
  if (!check.applicable) {
    e.summary.status = solvers::SolveStatus::kNotApplicable;
    e.summary.message = check.reason;
    return e;
  }
  TriNet dnet(frame.n), solved = centred;
  Eigen::MatrixX3d X;
  if (tri::interior_size(frame.n) > 0) {
    const tri::TriMaskSystem sys = tri::assemble_tri_mask_system(centred, mask);
    auto backend = solvers::make_solver(solver.name);
    e.summary = tri::solve_tri_system(sys, *backend, X);
    if (!e.summary.ok()) return e;
    solved = tri::fill_interior(centred, X);
    if (with_derivative) {
      Eigen::MatrixX3d dX = Eigen::MatrixX3d::Zero(sys.B.rows(), 3);
      const solvers::SolveSummary second = backend->solve(tri::tri_mask_sensitivity_rhs(solved), dX);
      if (!second.ok()) {
        e.summary = second;
        return e;
      }
      dnet = tri::fill_interior(dnet, dX);
    }
    e.net = tri::fill_interior(frame, X.rowwise() + centre);  // the data kept bit for bit
  }
  e.value = tri_objective_value(solved, objective);
  if (with_derivative) {
    e.has_derivative = true;
    for (const auto& [term, weight] : objective.terms)
      e.derivative += weight * (term == TriTerm::kTarget
                                    ? (objective.target ? target_derivative(solved, dnet, *objective.target) : 0.0)
                                    : quadratic_derivative(solved, dnet, term));
  }
  return e;
}

namespace {

class TriSearch {
 public:
  TriSearch(const TriNet& frame, const TriObjective& objective, const solvers::SolverInfo& solver,
            const AlphaSearchOptions& options)
      : frame_(frame), objective_(objective), solver_(solver), options_(options) {}

  AlphaSearchSummary run() {
    const auto start = std::chrono::steady_clock::now();
    if (!scan() && !flat()) {
      if (!on_bound()) refine(best_);
      refine_other_minima();
    }
    // failed evaluations, and a verdict resting on one (failed_region), as the α searches judge them
    detail::judge_failures(s_, log_);
    s_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    s_.evaluator = "factorize and solve";
    return s_;
  }

 private:
  TriEvaluation evaluate(double c, bool with_derivative) {
    TriEvaluation e = evaluate_tri_objective(frame_, objective_, c, solver_, with_derivative);
    ++s_.evaluations;
    s_.solves += with_derivative ? 2 : 1;
    log_.emplace_back(c, e.ok());
    if (!e.ok() && first_failure_.empty()) {
      s_.first_failure = e.summary.status;
      first_failure_ = "at " + solvers::format_g(c) + ": " + e.summary.brief_report();
    }
    return e;
  }

  bool scan() {
    const int k = options_.scan_points;
    const double step = (options_.upper - options_.lower) / (k - 1);
    for (int i = 0; i < k; ++i) {
      const double c = i + 1 == k ? options_.upper : options_.lower + i * step;
      grid_.push_back(evaluate(c, false));
      if (!grid_.back().ok()) grid_.back().value = HUGE_VAL;
      s_.scan.emplace_back(c, grid_.back().value);
    }
    int best = -1;
    for (int i = 0; i < k; ++i)
      if (grid_[i].ok() && (best < 0 || grid_[i].value < grid_[best].value)) best = i;
    if (best < 0) {
      s_.status = SearchStatus::kSolverFailed;
      s_.message = "every scan point failed: " + grid_[0].summary.brief_report();
      return true;
    }
    best_ = best;
    for (int i = 1; i + 1 < k; ++i)
      if (grid_[i].ok() && grid_[i - 1].ok() && grid_[i + 1].ok() && grid_[i].value < grid_[i - 1].value &&
          grid_[i].value <= grid_[i + 1].value)
        ++s_.local_minima;
    s_.value = grid_[best_].value;
    for (const auto& e : grid_)
      if (e.ok()) lo_ = std::min(lo_, e.value), hi_ = std::max(hi_, e.value);
    // A point that could not be solved (a singular member) is skipped, as in the α searches; only
    // a verdict that rests on it is withheld (judge_failures). Every failure made it failed_region,
    // also far from the optimum.
    const int failed = int(std::count_if(grid_.begin(), grid_.end(), [](const auto& e) { return !e.ok(); }));
    if (failed > 0)
      s_.message =
          std::to_string(failed) + " scan point(s) could not be solved and were skipped (first " + first_failure_ + ")";
    return false;
  }

  // Flat: the range is at rounding level, as the α searches judge it (search_run.h): rounding
  // errors of ε·diag in the net reach an energy of derivative order k amplified by nᵏ, so the floor
  // is 1e-16·diag²·n^(2k) (order 0 for the discrete energies); the mean squared distance to a
  // target, 1e-2·diag² per unit weight. Measured against the frame filled with its centroid, whose
  // energy is of the size of the boundary, a planar triangle with bumps of 5e-7 read as flat.
  bool flat() {
    // the boundary's box: the frame's interior holds zeros, which for a boundary at x = 1e15 made
    // the box 1e15 wide and the rounding floor of the energies larger than their spread
    const auto [lo, hi] = tri::boundary_box(frame_);
    const Eigen::Vector3d box = (hi - lo).transpose();
    // a boundary within rounding of one point (kPointExtent, as the rectangle's search) is flat:
    // its energies are noise, and the floor below, measured on the boundary, is noise-sized too
    const bool one_point = is_one_point(lo, hi);
    const double diag = box.norm(), n = std::max(frame_.n, 1);
    floor_ = 0;
    for (const auto& [term, weight] : objective_.terms) {
      const int order = term == TriTerm::kDirichlet                              ? 1
                        : term == TriTerm::kThinPlate || term == TriTerm::kTwist ? 2
                        : term == TriTerm::kE3                                   ? 3
                                                                                 : 0;
      floor_ +=
          weight * (term == TriTerm::kTarget ? 1e-2 * diag * diag : 1e-16 * diag * diag * std::pow(n, 2.0 * order));
    }
    const double size = std::max({std::abs(lo_), std::abs(hi_), floor_});
    if (!one_point && hi_ - lo_ > options_.flat_tolerance * size && tri::interior_size(frame_.n) > 0) return false;
    s_.flat = true;
    s_.status = SearchStatus::kFlat;
    s_.local_minima = 0;  // dips of rounding noise are no minima
    s_.message = "the objective does not depend on c over the bounds";
    return true;
  }

  bool on_bound() {
    const int k = int(grid_.size());
    if (best_ != 0 && best_ != k - 1) return false;
    const TriEvaluation e = evaluate(grid_[best_].parameter, true);
    if (!e.ok()) return fail(e);
    const bool outward = best_ == 0 ? e.derivative >= 0 : e.derivative <= 0;
    if (!outward) return false;
    s_.at_bound = true;
    s_.parameter = e.parameter;
    s_.value = e.value;
    return true;
  }

  bool fail(const TriEvaluation& e) {
    s_.status = SearchStatus::kFailedRegion;
    s_.message = "an evaluation next to the lowest one failed, at " + solvers::format_g(e.parameter) + ": " +
                 e.summary.brief_report() + "; no optimum is claimed";
    return true;
  }

  // From the best scan point downhill inside its neighbours' bracket to where the slope vanishes
  // (coons/alpha/downhill.h), singular members c*ₙ inside it included; at the end the slope
  // decides: not_converged where it has not vanished. (Golden section on the values of the
  // bracket, as before, crossed the singular members inside a wide one and reported a point 0.03
  // from the minimum as success.)
  void refine(int start) {
    const int k = int(grid_.size());
    const TriEvaluation& left = grid_[std::max(start - 1, 0)];
    const TriEvaluation& right = grid_[std::min(start + 1, k - 1)];
    const double a = left.parameter, b = right.parameter;
    if (!left.ok() || !right.ok()) return void(fail(left.ok() ? right : left));  // the bracket rests on it
    TriEvaluation g = evaluate(grid_[start].parameter, true);
    if (!g.ok()) return void(fail(g));
    const double end = g.derivative < 0 ? b : a;  // the neighbour downhill
    const detail::Downhill<TriEvaluation> d =
        detail::go_downhill([&](double c) { return evaluate(c, true); }, std::move(g), end,
                            options_.parameter_tolerance * (options_.upper - options_.lower),
                            4 * options_.max_iterations, [](const TriEvaluation& e) { return e.derivative == 0; });
    if (d.failed) return void(fail(*d.failed));  // (judge_failures would withhold the optimum anyway)
    const TriEvaluation& lo = d.lowest;
    s_.parameter = lo.parameter;
    s_.value = lo.value;
    s_.status = SearchStatus::kSuccess;
    s_.at_bound = lies_on_bound(lo.parameter, options_.lower, options_.upper);
    // a minimum: the slope vanishes on the scale of the scan's variation (as the α searches test it)
    if (!s_.at_bound && std::abs(lo.derivative) * (b - a) > 1e-6 * std::max(hi_ - lo_, floor_)) {
      s_.status = SearchStatus::kNotConverged;
      s_.message += std::string(s_.message.empty() ? "" : "; ") + "the refinement stopped where the slope is " +
                    solvers::format_g(lo.derivative) + ", not zero";
    }
  }

  // The other interior minima of the scan, refined as the lowest point was: over bounds that hold
  // singular members a narrow basin between them can hide the minimum (a degree-8 bump over
  // [−1, 1.5]: the lowest scan point, 1.1875, led to 3.4935 at c = 1.1737, while the scan point
  // −0.0625 leads to 3.2992 at c = −0.2444, the minimum that the bounds [−0.3, 0.3] find). The
  // lowest result is kept; a refinement that fails leaves the verdict of the others.
  void refine_other_minima() {
    if (s_.status != SearchStatus::kSuccess && s_.status != SearchStatus::kNotConverged) return;
    const int k = int(grid_.size());
    int refined = 0;
    const double first = *s_.parameter, first_value = s_.value;
    for (int i = 1; i + 1 < k; ++i) {
      if (i == best_ || !grid_[i].ok() || !grid_[i - 1].ok() || !grid_[i + 1].ok() ||
          !(grid_[i].value < grid_[i - 1].value && grid_[i].value <= grid_[i + 1].value))
        continue;
      ++refined;
      const auto kept = std::make_tuple(s_.parameter, s_.value, s_.status, s_.at_bound, s_.message);
      refine(i);
      const bool better = (s_.status == SearchStatus::kSuccess || s_.status == SearchStatus::kNotConverged) &&
                          s_.value < std::get<1>(kept);
      if (!better) std::tie(s_.parameter, s_.value, s_.status, s_.at_bound, s_.message) = kept;
    }
    if (refined > 0 && *s_.parameter != first)
      s_.message += std::string(s_.message.empty() ? "" : "; ") + "the scan saw " + std::to_string(refined + 1) +
                    " minima; each was refined and the lowest result kept (the lowest scan point led to c = " +
                    solvers::format_g(first) + ", value " + solvers::format_g(first_value) + ")";
  }

  const TriNet& frame_;
  const TriObjective& objective_;
  const solvers::SolverInfo& solver_;
  AlphaSearchOptions options_;
  AlphaSearchSummary s_;
  std::vector<TriEvaluation> grid_;
  std::vector<std::pair<double, bool>> log_;  //!< every evaluation: (c, succeeded)
  std::string first_failure_;                 //!< where the first failed evaluation was, and why
  double lo_ = HUGE_VAL, hi_ = -HUGE_VAL;     //!< the lowest and highest value of the solved scan points
  double floor_ = 0;                          //!< the objective's rounding floor (flat())
  int best_ = 0;
};

}  // namespace

AlphaSearchSummary search_tri_c(const TriNet& frame, const TriObjective& objective, const solvers::SolverInfo& solver,
                                const AlphaSearchOptions& options) {
  return TriSearch(frame, objective, solver, options).run();
}

}  // namespace coons
