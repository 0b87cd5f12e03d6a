// Internal to the α search (alpha_search.cpp, alpha_gamma_search.cpp): the Ceres pieces of the
// refinement of a scan's best point. An evaluator is any type with Evaluation evaluate(p) whose
// Evaluation has parameter, value, derivative and ok() (MaskObjective, the sine-basis objective).
//   BracketedObjective  f(centre + half·tanh θ) for Ceres's line search (BFGS), inside a bracket;
//   Stationarity        f'(α) = 0 with Jacobian f''(α) for Ceres's bounded trust region (Newton);
//   ShortStep           stops the trust region on an absolute step.
// Based on: Ceres Solver's GradientProblemSolver and Problem (S. Agarwal, K. Mierle et al.).
#pragma once

#include <ceres/ceres.h>

#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "coons/alpha/alpha_search.h"

namespace coons::detail {

//! The settings both Ceres minimisers share: silent, the iteration limit and parameter tolerance
//! of `options`, and the given function and gradient tolerances (on values in the normalised
//! frame, normalised_frame.h).
template <class CeresOptions>
void set_search_tolerances(CeresOptions& o, const AlphaSearchOptions& options, double function_tolerance,
                           double gradient_tolerance) {
  o.max_num_iterations = options.max_iterations;
  o.parameter_tolerance = options.parameter_tolerance;
  o.function_tolerance = function_tolerance;
  o.gradient_tolerance = gradient_tolerance;
  o.logging_type = ceres::SILENT;
}

// BFGS line search, silent, stopping on the parameter step (the objective is smooth and cheap
// to differentiate, so the curvature model pays off).
inline ceres::GradientProblemSolver::Options ceres_options(const AlphaSearchOptions& options) {
  ceres::GradientProblemSolver::Options o;
  o.line_search_direction_type = ceres::BFGS;
  // (the function tolerance stays out of the way: a relative change of 1e−15 in f leaves α*
  // only √(1e−15·f/f'') ≈ 1e−8 accurate)
  set_search_tolerances(o, options, 1e-20, 1e-14);
  return o;
}

// f(p(θ)) with p = centre + half·tanh θ keeps Ceres's unconstrained line search inside the bracket.
// The latest evaluation is kept: Ceres usually ends on it, and the caller needs it again.
template <class Obj>
class BracketedObjective : public ceres::FirstOrderFunction {
 public:
  using Evaluation = typename Obj::Evaluation;
  //! `latest` holds the latest evaluation only (for evaluate_once after the solve).
  BracketedObjective(Obj& objective, double centre, double half, bool& failed, std::vector<Evaluation>& latest)
      : objective_(objective), centre_(centre), half_(half), failed_(failed), latest_(latest) {}
  bool Evaluate(const double* theta, double* cost, double* gradient) const override {
    const double t = std::tanh(theta[0]);
    latest_.clear();
    latest_.push_back(objective_.evaluate(centre_ + half_ * t));
    const Evaluation& e = latest_.back();
    if (!e.ok()) {
      failed_ = true;
      return false;
    }
    *cost = e.value;
    if (gradient) gradient[0] = e.derivative * half_ * (1 - t * t);
    return true;
  }
  int NumParameters() const override { return 1; }

 private:
  Obj& objective_;
  double centre_, half_;
  bool& failed_;
  std::vector<Evaluation>& latest_;
};

// Objectives that know f'' (the sine-basis one) are refined by Ceres's bounded trust region on the
// stationarity condition f'(α) = 0 with Jacobian f''(α): Newton steps, a handful of evaluations.
template <class T, class = void>
struct HasSecondDerivative : std::false_type {};
template <class T>
struct HasSecondDerivative<T, std::void_t<decltype(std::declval<typename T::Evaluation>().second_derivative)>>
    : std::true_type {};

// Stops Ceres after an accepted step shorter than an absolute tolerance (Ceres's own
// parameter_tolerance is relative to |p|, which never triggers at an optimum α = 0).
class ShortStep : public ceres::IterationCallback {
 public:
  explicit ShortStep(double tolerance) : tolerance_(tolerance) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return summary.iteration > 0 && summary.step_is_successful && summary.step_norm <= tolerance_
               ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
               : ceres::SOLVER_CONTINUE;
  }

 private:
  double tolerance_;
};

// The evaluation at p from `seen`, or a new one appended to it.
template <class Obj>
const typename Obj::Evaluation& evaluate_once(Obj& objective, double p, std::vector<typename Obj::Evaluation>& seen) {
  for (const auto& e : seen)
    if (e.parameter == p) return e;
  seen.push_back(objective.evaluate(p));
  return seen.back();
}

template <class Obj>
class Stationarity : public ceres::SizedCostFunction<1, 1> {
 public:
  using Evaluation = typename Obj::Evaluation;
  Stationarity(Obj& objective, double scale, bool& failed, std::vector<Evaluation>& seen)
      : objective_(objective), scale_(scale), failed_(failed), seen_(seen) {}
  bool Evaluate(double const* const* p, double* residual, double** jacobian) const override {
    // Ceres asks for the same point more than once (the trial step, then its Jacobian): reuse it.
    const Evaluation& e = evaluate_once(objective_, p[0][0], seen_);
    if (!e.ok()) {
      failed_ = true;
      return false;
    }
    // f' at rounding level is zero: Ceres then stops on a zero cost instead of chasing noise
    residual[0] = std::abs(e.derivative) <= e.derivative_noise ? 0.0 : e.derivative / scale_;
    if (jacobian && jacobian[0]) jacobian[0][0] = e.second_derivative / scale_;
    return true;
  }

 private:
  Obj& objective_;
  double scale_;
  bool& failed_;
  std::vector<Evaluation>& seen_;  // the evaluations of the refinement, shared with the caller
};

}  // namespace coons::detail
