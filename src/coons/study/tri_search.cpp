#include "coons/study/tri_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

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
                  "' for a triangle (thin_plate, dirichlet, twist, discrete_thin_plate, discrete_dirichlet, "
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

TriEvaluation evaluate_tri_objective(const TriNet& frame, const TriObjective& objective, double c,
                                     const solvers::SolverInfo& solver, bool with_derivative) {
  TriEvaluation e;
  e.parameter = c;
  e.net = frame;
  const tri::TriMask mask{c};
  const tri::TriBackendCheck check = tri::check_tri_backend(solver, mask);
  e.summary.solver = solver.name;
  if (!check.applicable) {
    e.summary.status = solvers::SolveStatus::kNotApplicable;
    e.summary.message = check.reason;
    return e;
  }
  TriNet dnet(frame.n);
  if (tri::interior_size(frame.n) > 0) {
    const tri::TriMaskSystem sys = tri::assemble_tri_mask_system(frame, mask);
    auto backend = solvers::make_solver(solver.name);
    Eigen::MatrixX3d X;
    e.summary = tri::solve_tri_system(sys, *backend, X);
    if (!e.summary.ok()) return e;
    e.net = tri::fill_interior(frame, X);
    if (with_derivative) {
      Eigen::MatrixX3d dX = Eigen::MatrixX3d::Zero(sys.B.rows(), 3);
      const solvers::SolveSummary second = backend->solve(tri::tri_mask_sensitivity_rhs(e.net), dX);
      if (!second.ok()) {
        e.summary = second;
        return e;
      }
      dnet = tri::fill_interior(dnet, dX);
    }
  }
  e.value = tri_objective_value(e.net, objective);
  if (with_derivative) {
    e.has_derivative = true;
    for (const auto& [term, weight] : objective.terms)
      e.derivative += weight * (term == TriTerm::kTarget
                                    ? (objective.target ? target_derivative(e.net, dnet, *objective.target) : 0.0)
                                    : quadratic_derivative(e.net, dnet, term));
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
    if (!scan() && !flat() && !on_bound()) refine();
    s_.failed_intervals = detail::failed_runs(log_);  // runs of failures, as the α searches give them
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
    if (!e.ok() && s_.failed_evaluations++ == 0) s_.first_failure = e.summary.status;
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
    if (s_.failed_evaluations > 0) {
      s_.status = SearchStatus::kFailedRegion;
      s_.message = std::to_string(s_.failed_evaluations) + " scan point(s) could not be solved; no optimum is claimed";
      return true;
    }
    return false;
  }

  // The objective's natural scale: its value on the frame filled with the boundary's centroid.
  double scale() const {
    TriNet filled = frame_;
    const Eigen::RowVector3d centroid = frame_.points.colwise().mean();
    for (int k = 1; k <= frame_.n - 2; ++k)
      for (int j = 1; j <= frame_.n - 1 - k; ++j) filled.at(frame_.n - k - j, j, k) = centroid;
    return std::abs(tri_objective_value(filled, objective_));
  }

  bool flat() {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const auto& e : grid_) lo = std::min(lo, e.value), hi = std::max(hi, e.value);
    const double size = std::max({std::abs(lo), std::abs(hi), scale()});
    if (hi - lo > options_.flat_tolerance * size && tri::interior_size(frame_.n) > 0) return false;
    s_.flat = true;
    s_.status = SearchStatus::kFlat;
    s_.local_minima = 0;  // dips of rounding noise are no minima
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
    s_.message = "an evaluation near the optimum failed: " + e.summary.brief_report();
    return true;
  }

  // Secant steps on f′ = 0 in [a, b] with f′(a) < 0 < f′(b), a bisection whenever the previous step
  // did not halve the bracket (so it halves at least every two steps); golden section on the
  // values when the derivative does not change sign there.
  void refine() {
    const int k = int(grid_.size());
    double a = grid_[std::max(best_ - 1, 0)].parameter, b = grid_[std::min(best_ + 1, k - 1)].parameter;
    TriEvaluation ea = evaluate(a, true), eb = evaluate(b, true);
    if (!ea.ok()) return void(fail(ea));
    if (!eb.ok()) return void(fail(eb));
    const double tolerance = options_.parameter_tolerance * (options_.upper - options_.lower);
    TriEvaluation best = grid_[best_];
    if (ea.derivative < 0 && eb.derivative > 0) {
      bool bisect = false;
      for (int it = 0; it < 2 * options_.max_iterations && eb.parameter - ea.parameter > tolerance; ++it) {
        const double lo = ea.parameter, hi = eb.parameter;
        double c = hi - eb.derivative * (hi - lo) / (eb.derivative - ea.derivative);
        if (bisect || !(c > lo && c < hi)) c = (lo + hi) / 2;
        const TriEvaluation e = evaluate(c, true);
        if (!e.ok()) return void(fail(e));
        if (e.value < best.value) best = e;
        if (e.derivative == 0) break;
        (e.derivative < 0 ? ea : eb) = e;
        bisect = !bisect && eb.parameter - ea.parameter > (hi - lo) / 2;
      }
    } else {
      const double g = (std::sqrt(5.0) - 1) / 2;
      for (int it = 0; it < options_.max_iterations && b - a > tolerance; ++it) {
        const double x1 = b - g * (b - a), x2 = a + g * (b - a);
        const TriEvaluation e1 = evaluate(x1, false), e2 = evaluate(x2, false);
        if (!e1.ok()) return void(fail(e1));
        if (!e2.ok()) return void(fail(e2));
        if (e1.value < best.value) best = e1;
        if (e2.value < best.value) best = e2;
        if (e1.value < e2.value)
          b = x2;
        else
          a = x1;
      }
    }
    if (ea.ok() && ea.value < best.value) best = ea;
    if (eb.ok() && eb.value < best.value) best = eb;
    s_.parameter = best.parameter;
    s_.value = best.value;
    s_.status = SearchStatus::kSuccess;
    // the refinement can end on a bound (the scan's best point there, its slope not pointing out)
    const double edge = 1e-7 * (options_.upper - options_.lower);
    if (std::abs(best.parameter - options_.lower) <= edge || std::abs(best.parameter - options_.upper) <= edge)
      s_.at_bound = true;
  }

  const TriNet& frame_;
  const TriObjective& objective_;
  const solvers::SolverInfo& solver_;
  AlphaSearchOptions options_;
  AlphaSearchSummary s_;
  std::vector<TriEvaluation> grid_;
  std::vector<std::pair<double, bool>> log_;  //!< every evaluation: (c, succeeded)
  int best_ = 0;
};

}  // namespace

AlphaSearchSummary search_tri_c(const TriNet& frame, const TriObjective& objective, const solvers::SolverInfo& solver,
                                const AlphaSearchOptions& options) {
  return TriSearch(frame, objective, solver, options).run();
}

}  // namespace coons
