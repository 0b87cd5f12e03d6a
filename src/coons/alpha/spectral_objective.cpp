#include "spectral_objective.h"

#include <cassert>
#include <cmath>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/sine_basis.h"

namespace coons {

SpectralAlphaObjective::SpectralAlphaObjective(const Boundary& b, std::vector<std::pair<DiscreteEnergy, double>> terms)
    : rows_(b.m - 1), cols_(b.n - 1), terms_(std::move(terms)) {
  assert(rows_ >= 1 && cols_ >= 1 && !terms_.empty());
  const ControlNet frame = frame_net(b);
  // The linear term: ∂E/∂N at N = 0 is 2c; E₀ = E(frame).
  Eigen::MatrixX3d c = Eigen::MatrixX3d::Zero(Eigen::Index(rows_) * cols_, 3);
  for (const auto& [kind, weight] : terms_) {
    e0_ += weight * discrete_energy_form(frame, frame, kind);
    c += 0.5 * weight * interior_of(discrete_energy_gradient(frame, kind));
  }
  const Eigen::MatrixXd K = solvers::sine_transform_2d(mask_rhs(frame, Mask9{0, 0, 1}), rows_, cols_);
  const Eigen::MatrixXd E = solvers::sine_transform_2d(mask_rhs(frame, Mask9{1, 1, 0}), rows_, cols_);
  const Eigen::MatrixXd C = solvers::sine_transform_2d(c, rows_, cols_);
  kk_ = K.cwiseProduct(K).rowwise().sum().array();
  ke_ = K.cwiseProduct(E).rowwise().sum().array();
  ee_ = E.cwiseProduct(E).rowwise().sum().array();
  ck_ = C.cwiseProduct(K).rowwise().sum().array();
  ce_ = C.cwiseProduct(E).rowwise().sum().array();
  x_.resize(rows_);
  y_.resize(cols_);
  for (int p = 0; p < rows_; ++p) x_(p) = std::cos(M_PI * (p + 1) / (rows_ + 1));
  for (int q = 0; q < cols_; ++q) y_(q) = std::cos(M_PI * (q + 1) / (cols_ + 1));
}

SpectralAlphaObjective::Value SpectralAlphaObjective::evaluate(double alpha) const {
  const double beta = 0.25 - alpha;
  double f = e0_, df = 0, d2f = 0;
  bool ok = true;
  for (int p = 0; p < rows_; ++p) {
    const double x = x_(p), a = 2 - 2 * x;
    const Eigen::Index base = Eigen::Index(p) * cols_;
    for (int q = 0; q < cols_; ++q) {
      const double y = y_(q), bq = 2 - 2 * y, s = x + y, t = x * y;
      double sym = 0;
      for (const auto& [kind, weight] : terms_) {
        switch (kind) {
          case DiscreteEnergy::kTwist: sym += weight * a * bq; break;
          case DiscreteEnergy::kDirichlet: sym += weight * (a + bq); break;
          case DiscreteEnergy::kThinPlate: sym += weight * (a * a + 2 * a * bq + bq * bq); break;
        }
      }
      const Eigen::Index k = base + q;
      const double lambda = 1 - 2 * beta * s - 4 * alpha * t, dl = 2 * s - 4 * t;
      if (std::abs(lambda) < 1e-14) ok = false;
      const double il = 1 / lambda;
      const double u = alpha * alpha * kk_(k) + 2 * alpha * beta * ke_(k) + beta * beta * ee_(k);
      const double du = 2 * alpha * kk_(k) + 2 * (beta - alpha) * ke_(k) - 2 * beta * ee_(k);
      const double d2u = 2 * kk_(k) - 4 * ke_(k) + 2 * ee_(k);
      const double v = alpha * ck_(k) + beta * ce_(k), dv = ck_(k) - ce_(k);
      f += sym * u * il * il + 2 * v * il;
      df += sym * (du * il * il - 2 * u * dl * il * il * il) + 2 * (dv * il - v * dl * il * il);
      d2f += sym * (d2u * il * il - 4 * du * dl * il * il * il + 6 * u * dl * dl * il * il * il * il) +
             2 * (-2 * dv * dl * il * il + 2 * v * dl * dl * il * il * il);
    }
  }
  return {f, df, d2f, ok && std::isfinite(f)};
}

SpectralAlphaSearchObjective::SpectralAlphaSearchObjective(const Boundary& boundary, Objective objective)
    : boundary_(boundary), objective_(std::move(objective)), spectral_(boundary, objective_.discrete) {}

SpectralAlphaSearchObjective::Evaluation SpectralAlphaSearchObjective::evaluate(double alpha, bool) {
  ++evaluations_;
  const SpectralAlphaObjective::Value v = spectral_.evaluate(alpha);
  Evaluation e;
  e.parameter = alpha;
  e.value = v.value;
  e.derivative = v.derivative;
  e.summary.solver = "spectral";
  e.summary.iterations = 0;
  if (!v.ok) {
    e.summary.status = solvers::SolveStatus::kSingular;
    e.summary.message = "a mode's eigenvalue vanishes at this alpha";
  }
  return e;
}

}  // namespace coons
