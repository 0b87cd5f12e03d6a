#include "spectral_objective.h"

#include <cassert>
#include <cmath>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask_families.h"
#include "coons/net/coons_net.h"
#include "solvers/sine_basis.h"

namespace coons {

SpectralAlphaObjective::SpectralAlphaObjective(const Boundary& b, std::vector<std::pair<DiscreteEnergy, double>> terms)
    : rows_(b.m - 1), cols_(b.n - 1), terms_(std::move(terms)) {
  assert(rows_ >= 1 && cols_ >= 1 && !terms_.empty());
  // Measure everything from the discrete Coons net N_C (the α = −1/4 solution): N(α) = N_C + δ(α)
  // with A(α) δ = (α + 1/4)·R, R = E(N_C) − 4 N_C its 5-point Laplacian (the α = −1/4 mask gives
  // K(N_C) − 4N_C = 2R). Then f = E(N_C) + 2 c·δ + E(δ) holds only small terms: no cancellation
  // against the large energy of the bare frame, even at N = 1023.
  const ControlNet coons = discrete_coons_net(b);
  const Eigen::MatrixX3d R = mask_sensitivity_rhs(coons, Mask9{1, 1, 0}) - 4 * interior_of(coons);
  Eigen::MatrixX3d c = Eigen::MatrixX3d::Zero(R.rows(), 3);
  for (const auto& [kind, weight] : terms_) {
    e0_ += weight * discrete_energy_form(coons, coons, kind);
    c += 0.5 * weight * interior_of(discrete_energy_gradient(coons, kind));
  }
  const Eigen::MatrixXd R_hat = solvers::sine_transform_2d(R, rows_, cols_);
  const Eigen::MatrixXd C_hat = solvers::sine_transform_2d(c, rows_, cols_);
  rr_ = R_hat.cwiseProduct(R_hat).rowwise().sum().array();
  cr_ = C_hat.cwiseProduct(R_hat).rowwise().sum().array();
  // the energy's symbol: A2·(a² + b²) + AB·a·b + A1·(a + b), a = 2 − 2x, b = 2 − 2y
  for (const auto& [kind, weight] : terms_) {
    switch (kind) {
      case DiscreteEnergy::kTwist: sym_ab_ += weight; break;
      case DiscreteEnergy::kDirichlet: sym_a1_ += weight; break;
      case DiscreteEnergy::kThinPlate:
        sym_a2_ += weight;
        sym_ab_ += 2 * weight;
        break;
    }
  }
  x_.resize(rows_);
  y_.resize(cols_);
  for (int p = 0; p < rows_; ++p) x_(p) = std::cos(M_PI * (p + 1) / (rows_ + 1));
  for (int q = 0; q < cols_; ++q) y_(q) = std::cos(M_PI * (q + 1) / (cols_ + 1));
}

SpectralAlphaObjective::Value SpectralAlphaObjective::evaluate(double alpha) const {
  // per mode: δ̂ = γ R̂/λ, γ = α + 1/4, λ = 1 − 2β(x + y) − 4αxy;
  // f = E(N_C) + Σ [ sym·γ²·rr/λ² + 2γ·cr/λ ]
  const double beta = 0.25 - alpha, gamma = alpha + 0.25;
  double f = e0_, df = 0, d2f = 0, smallest = HUGE_VAL;
  const Eigen::ArrayXd y = y_.array(), b = 2 - 2 * y;
  for (int p = 0; p < rows_; ++p) {  // one grid row of modes at a time, as Eigen array expressions
    const double x = x_(p), a = 2 - 2 * x;
    const Eigen::Index base = Eigen::Index(p) * cols_;
    const auto rr = rr_.segment(base, cols_);
    const auto cr = cr_.segment(base, cols_);
    const Eigen::ArrayXd s = x + y, t = x * y;
    const Eigen::ArrayXd sym = sym_a2_ * (a * a + b.square()) + sym_ab_ * a * b + sym_a1_ * (a + b);
    const Eigen::ArrayXd lambda = 1 - 2 * beta * s - 4 * alpha * t, dl = 2 * s - 4 * t;
    const Eigen::ArrayXd il = lambda.inverse();
    const Eigen::ArrayXd g = dl * il;  // λ'/λ
    const Eigen::ArrayXd quad = sym * rr * il.square(), lin = 2 * cr * il;
    f += (gamma * gamma * quad + gamma * lin).sum();
    df += (quad * (2 * gamma - 2 * gamma * gamma * g) + lin * (1 - gamma * g)).sum();
    d2f += (quad * (2 - 8 * gamma * g + 6 * gamma * gamma * g.square()) + lin * (2 * gamma * g.square() - 2 * g)).sum();
    smallest = std::min(smallest, lambda.abs().minCoeff());
  }
  return {f, df, d2f, smallest >= 1e-14 && std::isfinite(f)};
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
  e.second_derivative = v.second_derivative;
  e.summary.solver = "spectral";
  e.summary.iterations = 0;
  if (!v.ok) {
    e.summary.status = solvers::SolveStatus::kSingular;
    e.summary.message = "a mode's eigenvalue vanishes at this alpha";
  }
  return e;
}

}  // namespace coons
