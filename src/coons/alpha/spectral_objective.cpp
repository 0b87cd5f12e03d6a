#include "spectral_objective.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

#include "coons/alpha/spectral_modes.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "solvers/sine_basis.h"

namespace coons {

namespace {

using detail::basis_at_samples;
using detail::mode_row;
using FC = detail::FactorColumns;

// The sides of the frame as frame_net reads them (corners from bottom and top): along i the
// columns j = 0 and j = n, along j the rows i = 0 and i = m; each #len+1 by 3.
struct Sides {
  Eigen::MatrixX3d bottom, top, left, right;
};
Sides frame_sides(const Boundary& b) {
  Sides s{b.bottom, b.top, b.left, b.right};
  s.left.row(0) = b.bottom.row(0);
  s.left.row(b.n) = b.top.row(0);
  s.right.row(0) = b.bottom.row(b.m);
  s.right.row(b.n) = b.top.row(b.m);
  return s;
}

// D^order F: forward differences of the columns (#rows − order rows).
Eigen::MatrixXd differences(Eigen::MatrixXd F, int order) {
  for (int k = 0; k < order; ++k) F = (F.bottomRows(F.rows() - 1) - F.topRows(F.rows() - 1)).eval();
  return F;
}

// (D^order)ᵀ D^order F at the interior points 1..len−1 of columns F (#len+1 rows): half the
// gradient of Σ‖D^order f‖² there.
Eigen::MatrixXd normal_interior(const Eigen::MatrixXd& F, int order) {
  Eigen::MatrixXd d = differences(F, order);
  for (int k = 0; k < order; ++k) {  // the adjoint of one forward difference
    Eigen::MatrixXd up = Eigen::MatrixXd::Zero(d.rows() + 1, d.cols());
    up.bottomRows(d.rows()) += d;
    up.topRows(d.rows()) -= d;
    d = std::move(up);
  }
  return d.middleRows(1, F.rows() - 2);
}

// Σ over a grid of (Σ_t A(i, t)·B(j, t))² = Σ_{t,s} (AᵀA)_ts (BᵀB)_ts.
double separable_square_sum(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return ((A.transpose() * A).array() * (B.transpose() * B).array()).sum();
}

}  // namespace

bool SpectralAlphaObjective::supports(const Objective& o) {
  const bool target = o.target_weight > 0;
  return (!o.discrete.empty() || !o.energy.empty() || target) && (!target || o.target);
}

SpectralAlphaObjective::SpectralAlphaObjective(const Boundary& b, const Objective& objective)
    : rows_(b.m - 1), cols_(b.n - 1) {
  assert(rows_ >= 1 && cols_ >= 1 && supports(objective));
  // Measured from the discrete Coons net N_C (the α = −1/4 solution): N(α) = N_C + δ(α) with
  // A(α) δ = (α + 1/4)·R, R the 5-point Laplacian of N_C. Then f = E(N_C) + 2 c·δ + E(δ), c the
  // halved gradient of E at N_C: only small terms, no cancellation against the energy of the frame.
  //
  // N_C is a boolean sum of linear blends, per coordinate A·Bᵀ of rank 4:
  //   A = [1 − i/m, i/m, bottom(i), top(i)],  B = [left′(j), right′(j), 1 − j/n, j/n]
  // (left′ = left minus the linear blend of its end points). Each energy is Σ w‖Δ_i^a Δ_j^b N‖²
  // (difference_terms), whose Hessian is w·(K_a ⊗ K_b), K_a = (D^a)ᵀD^a. Hence, with K_1, K_2 of a
  // linear column vanishing at the interior points:
  //   E(N_C) = Σ w Σ_xyz ⟨(D^a A)ᵀ(D^a A), (D^b B)ᵀ(D^b B)⟩
  //   R = −K_1 bottom ⊗ (1 − j/n) − K_1 top ⊗ j/n − (1 − i/m) ⊗ K_1 left′ − i/m ⊗ K_1 right′
  //   c = Σ_{b=0} w K_a bottom ⊗ (1 − j/n) + … + Σ_{a=0} w (1 − i/m) ⊗ K_b left′ + …
  // (terms with a, b ≥ 1 leave nothing inside: the Coons net minimises the discrete twist). The 2-D
  // sine transform of u ⊗ v is û ⊗ v̂: the set-up is O(N log N) plus one pass to fill the modes.
  std::vector<DifferenceTerm> energy;
  for (const auto& [kind, weight] : objective.discrete)
    for (DifferenceTerm t : difference_terms(kind)) {
      t.weight *= weight;
      energy.push_back(t);
    }
  const Sides sides = frame_sides(b);
  const int m = b.m, n = b.n;
  const Eigen::VectorXd si = Eigen::VectorXd::LinSpaced(m + 1, 0, 1), sj = Eigen::VectorXd::LinSpaced(n + 1, 0, 1);
  Eigen::MatrixXd A[3], B[3];                  // N_C = A[c]·B[c]ᵀ per coordinate
  Eigen::MatrixXd Ui(m + 1, 6), Vj(n + 1, 6);  // the sides: [bottom | top], [left′ | right′]
  Ui << sides.bottom, sides.top;
  Vj.leftCols(3) = sides.left - (1 - sj.array()).matrix() * sides.left.row(0) - sj * sides.left.row(n);
  Vj.middleCols(3, 3) = sides.right - (1 - sj.array()).matrix() * sides.right.row(0) - sj * sides.right.row(n);
  for (int c = 0; c < 3; ++c) {
    A[c].resize(m + 1, 4);
    B[c].resize(n + 1, 4);
    A[c] << 1 - si.array(), si, Ui.col(c), Ui.col(3 + c);
    B[c] << Vj.col(c), Vj.col(3 + c), 1 - sj.array(), sj;
    for (const DifferenceTerm& t : energy)
      e0_ += t.weight * separable_square_sum(differences(A[c], t.i_order), differences(B[c], t.j_order));
  }
  // Factors at the interior points, sine-transformed, in the blocks of FactorColumns.
  auto factors = [&](const Eigen::MatrixXd& sides6, const Eigen::MatrixXd& blends, bool i_direction) {
    const Eigen::Index k = sides6.rows() - 2;
    Eigen::MatrixXd F = Eigen::MatrixXd::Zero(k, FC::kCount);
    F.middleCols(FC::kRSide, 6) = -normal_interior(sides6, 1);
    for (const DifferenceTerm& t : energy) {
      const int order = i_direction ? t.i_order : t.j_order, other = i_direction ? t.j_order : t.i_order;
      if (other == 0) F.middleCols(FC::kCSide, 6) += t.weight * normal_interior(sides6, order);
    }
    F.middleCols(FC::kBlend, 2) = blends.middleRows(1, k);
    return solvers::sine_transform_1d(F);
  };
  const Eigen::MatrixXd U = factors(Ui, A[0].leftCols(2), true);    // rows_ × FC::kCount
  const Eigen::MatrixXd V = factors(Vj, B[0].rightCols(2), false);  // cols_ × FC::kCount

  // ξ = 1 − cos θ = 2 sin²(θ/2) without the cancellation of 1 − cos for the low modes, whose
  // eigenvalues (ξη at α = −1/4, ~1e-11 at N = 1023) carry the whole answer near −1/4.
  auto one_minus_cos = [](int count) {
    Eigen::VectorXd v(count);
    for (int k = 0; k < count; ++k) v(k) = 2 * std::pow(std::sin(M_PI * (k + 1) / (2.0 * (count + 1))), 2);
    return v;
  };
  xi_ = one_minus_cos(rows_);
  eta_ = one_minus_cos(cols_);

  if (!objective.energy.empty() || objective.target_weight > 0) {
    // R̂ made dense from its four separable parts (FactorColumns of U and V)
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd Ur(rows_, 4), Vr(cols_, 4);
      Ur << U.col(FC::of(FC::kRSide, 0, c)), U.col(FC::of(FC::kRSide, 1, c)), U.col(FC::kBlend), U.col(FC::kBlend + 1);
      Vr << V.col(FC::kBlend), V.col(FC::kBlend + 1), V.col(FC::of(FC::kRSide, 0, c)), V.col(FC::of(FC::kRSide, 1, c));
      r_hat_[c] = Ur * Vr.transpose();
    }
    const ControlNet coons = discrete_coons_net(b);
    if (!objective.energy.empty()) {
      exact_ = exact_energies(coons, objective.energy, A, B);
    }
    if (objective.target_weight > 0) {
      target_weight_ = objective.target_weight;
      target_ = objective.target;
      const int k = target_->samples;
      const Eigen::MatrixXd Bu = basis_at_samples(b.m, k), Bv = basis_at_samples(b.n, k);
      p_ = solvers::sine_transform_1d(Bu.middleCols(1, rows_).transpose()).transpose();
      q_ = solvers::sine_transform_1d(Bv.middleCols(1, cols_).transpose()).transpose();
      for (int c = 0; c < 3; ++c) coons_samples_[c] = Bu * coordinate_grid(coons, c) * Bv.transpose();
      if (target_->kind == Target::Kind::kNet) {  // the differences to its samples (objective.cpp)
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        const Eigen::MatrixX3d T = sample_surface(target_->net, k, k);
        for (int c = 0; c < 3; ++c) coons_samples_[c] -= Eigen::Map<const RowMajor>(T.col(c).data(), k, k);
      }
    }
  }
  if (energy.empty()) return;  // no discrete terms

  // Per mode: quad = symbol·Σ_xyz R̂², lin = 2·Σ_xyz ĉ·R̂, with the energy's symbol
  // Σ w (2 − 2x)^a (2 − 2y)^b (the eigenvalues of K_a ⊗ K_b on grids vanishing at the frame).
  quad_.resize(Eigen::Index(rows_) * cols_);
  lin_.resize(quad_.size());
  const Eigen::ArrayXd kb = 2 * eta_.array();
  const Eigen::ArrayXd kb_power[3] = {Eigen::ArrayXd::Ones(cols_), kb, kb.square()};  // orders ≤ 2
  Eigen::ArrayXd symbol(cols_);
  for (int p = 0; p < rows_; ++p) {
    const double ka = 2 * xi_(p);
    symbol.setZero();
    for (const DifferenceTerm& t : energy) symbol += t.weight * std::pow(ka, t.i_order) * kb_power[t.j_order];
    const Eigen::Matrix<double, FC::kCount, 1> u = U.row(p).transpose();
    const Eigen::Index base = Eigen::Index(p) * cols_;
    mode_row(u.data(), V.data(), cols_, symbol.data(), quad_.data() + base, lin_.data() + base);
  }
}

SpectralAlphaSearchObjective::SpectralAlphaSearchObjective(const Boundary& boundary, Objective objective)
    : boundary_(boundary),
      objective_(std::move(objective)),
      unit_(normalised_frame(boundary_, objective_)),
      spectral_(unit_.boundary, unit_.objective) {}

SpectralAlphaSearchObjective::Evaluation SpectralAlphaSearchObjective::evaluate(double alpha, bool) {
  ++evaluations_;
  const SpectralAlphaObjective::Value v = spectral_.evaluate(alpha);
  Evaluation e;
  e.parameter = alpha;
  const double k = unit_.value_factor;  // a power of two: exact
  e.value = k * v.value;
  e.derivative = k * v.derivative;
  e.second_derivative = k * v.second_derivative;
  e.derivative_noise = k * v.derivative_noise;
  e.summary.solver = "spectral";
  e.summary.iterations = 0;
  if (!v.ok) {
    e.summary.status = solvers::SolveStatus::kSingular;
    e.summary.message = "a mode's eigenvalue vanishes at this alpha";
  }
  return e;
}

}  // namespace coons
