#include "stencil.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace coons {

namespace {

constexpr double kPi = 3.14159265358979323846;

const Eigen::Matrix<double, 5, 1> kDelta4 = (Eigen::Matrix<double, 5, 1>() << 1, -4, 6, -4, 1).finished();

Eigen::MatrixXd c1_raw() { return kDelta4 * kDelta4.transpose(); }

Eigen::MatrixXd biharmonic_raw() {
  Eigen::MatrixXd T(5, 5);
  T << 0, 0, 1, 0, 0,    //
      0, 2, -8, 2, 0,    //
      1, -8, 20, -8, 1,  //
      0, 2, -8, 2, 0,    //
      0, 0, 1, 0, 0;
  return T;
}

}  // namespace

Stencil make_stencil(const Eigen::MatrixXd& raw) {
  assert((raw.rows() == 3 || raw.rows() == 5) && raw.cols() == raw.rows());
  Stencil s;
  s.radius = int(raw.rows() / 2);
  const double centre = raw(s.radius, s.radius);
  assert(centre != 0);
  s.weights = raw / centre;
  s.weights(s.radius, s.radius) = 1;
  return s;
}

Stencil trimmed(const Stencil& s) {
  if (s.radius != 2) return s;
  const Eigen::MatrixXd& W = s.weights;
  const double inner = W.block(1, 1, 3, 3).cwiseAbs().sum();
  if (W.cwiseAbs().sum() != inner) return s;
  Stencil t;
  t.radius = 1;
  t.weights = W.block(1, 1, 3, 3);
  return t;
}

Stencil alpha_stencil(const Mask9& mask) {
  Stencil s;
  s.radius = 1;
  // rows run along i: W(±1, 0) = weights(1 ± 1, 1) = −e_i, W(0, ±1) = weights(1, 1 ± 1) = −e_j.
  s.weights = Eigen::MatrixXd::Constant(3, 3, -mask.diag);
  s.weights(0, 1) = s.weights(2, 1) = -mask.edge_i;
  s.weights(1, 0) = s.weights(1, 2) = -mask.edge_j;
  s.weights(1, 1) = 1;
  return s;
}

std::optional<Mask9> to_mask9(const Stencil& s0) {
  const Stencil s = trimmed(s0);
  if (s.radius != 1) return std::nullopt;
  const Eigen::MatrixXd& W = s.weights;
  const bool reflective =
      W(0, 1) == W(2, 1) && W(1, 0) == W(1, 2) && W(0, 0) == W(0, 2) && W(0, 0) == W(2, 0) && W(0, 0) == W(2, 2);
  if (!reflective) return std::nullopt;
  Mask9 mask;
  mask.edge_i = -W(0, 1);
  mask.edge_j = -W(1, 0);
  mask.diag = -W(0, 0);
  return mask;
}

Stencil c1_coons_stencil() { return make_stencil(c1_raw()); }

Stencil biharmonic_stencil() { return make_stencil(biharmonic_raw()); }

Stencil c1_family_stencil(double w) { return make_stencil(w * c1_raw() + (1 - w) * biharmonic_raw()); }

Eigen::MatrixXd c1_family_stencil_derivative(double w) {
  const double c = 20 + 16 * w;
  return (20 * c1_raw() - 36 * biharmonic_raw()) / (c * c);
}

double weight_sum(const Stencil& s) { return s.weights.sum(); }

double symmetry_defect(const Stencil& s) { return (s.weights - s.weights.reverse()).cwiseAbs().maxCoeff(); }

double stencil_symbol(const Stencil& s, double theta, double phi) {
  double sigma = 0;
  for (int a = -s.radius; a <= s.radius; ++a)
    for (int b = -s.radius; b <= s.radius; ++b) sigma += s.at(a, b) * std::cos(a * theta + b * phi);
  return sigma;
}

namespace {

// σ at (θ, φ) with its gradient and Hessian.
struct SymbolJet {
  double value = 0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();
};

SymbolJet symbol_jet(const Stencil& s, const Eigen::Vector2d& x) {
  SymbolJet j;
  for (int a = -s.radius; a <= s.radius; ++a)
    for (int b = -s.radius; b <= s.radius; ++b) {
      const double w = s.at(a, b);
      if (w == 0) continue;
      const double c = std::cos(a * x(0) + b * x(1)), sn = std::sin(a * x(0) + b * x(1));
      const Eigen::Vector2d k(a, b);
      j.value += w * c;
      j.gradient -= w * sn * k;
      j.hessian -= w * c * k * k.transpose();
    }
  return j;
}

// The smallest σ reached by a damped Newton descent from x (Levenberg shift where the Hessian is
// not positive definite, steps halved until σ decreases). Where the Hessian has negative curvature
// the eigenvector's direction (length `reach`) is tried too: a sample can sit exactly on a saddle
// or maximum of σ (zero gradient, e.g. θ = 0 of an even symbol) with the dip beside it.
double descend_symbol(const Stencil& s, Eigen::Vector2d x, double reach) {
  SymbolJet j = symbol_jet(s, x);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(j.hessian);
    const double scale = 1 + j.hessian.cwiseAbs().maxCoeff();
    const double lowest = eig.eigenvalues()(0);
    const double shift = std::max(0.0, -lowest) + 1e-12 * scale;
    std::vector<Eigen::Vector2d> directions = {
        -(j.hessian + shift * Eigen::Matrix2d::Identity()).ldlt().solve(j.gradient)};
    if (lowest < 0) {
      directions.emplace_back(reach * eig.eigenvectors().col(0));
      directions.emplace_back(-reach * eig.eigenvectors().col(0));
    }
    std::optional<std::pair<Eigen::Vector2d, SymbolJet>> best;
    for (Eigen::Vector2d step : directions)
      for (int halving = 0; halving < 40 && step.norm() > 1e-15; ++halving, step /= 2) {
        const SymbolJet next = symbol_jet(s, x + step);
        if (next.value < j.value) {
          if (!best || next.value < best->second.value) best.emplace(step, next);
          break;
        }
      }
    if (!best) break;
    x += best->first;
    j = best->second;
  }
  return j.value;
}

}  // namespace

bool symbol_nonnegative(const Stencil& s, double tolerance) {
  constexpr int kSamples = 256;  // a multiple of 2: 0 and π are sample points
  const double h = 2 * kPi / kSamples;
  Eigen::MatrixXd sigma(kSamples, kSamples);
  for (int p = 0; p < kSamples; ++p)
    for (int q = 0; q < kSamples; ++q) {
      sigma(p, q) = stencil_symbol(s, p * h, q * h);
      if (sigma(p, q) < -tolerance) return false;
    }
  // A dip between samples lies next to a sampled local minimum: descend from each one (periodic
  // neighbours; plateaus, as in a symbol of θ alone, give many starts, each a few evaluations).
  const auto wrap = [](int k) { return (k + kSamples) % kSamples; };
  for (int p = 0; p < kSamples; ++p)
    for (int q = 0; q < kSamples; ++q) {
      bool minimum = true;
      for (int dp = -1; dp <= 1 && minimum; ++dp)
        for (int dq = -1; dq <= 1 && minimum; ++dq) minimum = sigma(wrap(p + dp), wrap(q + dq)) >= sigma(p, q);
      if (minimum && descend_symbol(s, Eigen::Vector2d(p * h, q * h), h / 2) < -tolerance) return false;
    }
  return true;
}

std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> separable_factors(const Stencil& s) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.weights, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  if (!(sv(0) > 0) || sv(1) > 1e-13 * sv(0)) return std::nullopt;
  Eigen::VectorXd u = svd.matrixU().col(0) * std::sqrt(sv(0));
  Eigen::VectorXd v = svd.matrixV().col(0) * std::sqrt(sv(0));
  // Make the product of the centres exactly the centre weight (1) and symmetrise against rounding.
  const double cu = u(s.radius), cv = v(s.radius);
  if (cu == 0 || cv == 0) return std::nullopt;
  u /= cu;
  v *= cu;
  u = 0.5 * (u + u.reverse().eval());
  v = 0.5 * (v + v.reverse().eval());
  return std::make_pair(u, v);
}

}  // namespace coons
