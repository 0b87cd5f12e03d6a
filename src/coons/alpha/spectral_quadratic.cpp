// The quadratic terms of the sine-basis objective (spectral_objective.h) whose Hessians are dense
// Kronecker products: the exact energies of the surface, as constant + 2⟨ĉ, δ̂⟩ + Σ w⟨δ̂, K̂_a δ̂ K̂_b⟩
// in the sine basis of the interior.
// Sizes: a rows × rows and a cols × cols matrix per term.
#include <Eigen/Core>

#include "coons/alpha/spectral_modes.h"
#include "coons/alpha/spectral_objective.h"
#include "coons/net/bernstein.h"
#include "solvers/sine_basis.h"

namespace coons {

namespace {

// K_a = D_aᵀ G D_a ((k+1) × (k+1)): ∫(∂^a f)² = fᵀ K_a f for f in the Bernstein basis of degree k,
// D_a the derivative's coefficients k!/(k−a)!·Δ^a and G the Gram matrix of degree k − a.
Eigen::MatrixXd derivative_gram(int k, int a) {
  if (a > k) return Eigen::MatrixXd::Zero(k + 1, k + 1);
  Eigen::MatrixXd D = Eigen::MatrixXd::Identity(k + 1, k + 1);
  for (int r = 0; r < a; ++r) D = ((k - r) * (D.bottomRows(D.rows() - 1) - D.topRows(D.rows() - 1))).eval();
  return D.transpose() * bernstein_gram(k - a) * D;
}

// S_r·G·S_c: the 2-D sine transform of a rows × cols grid held as a matrix.
Eigen::MatrixXd sine_2d(const Eigen::MatrixXd& G) {
  return solvers::sine_transform_1d(solvers::sine_transform_1d(G).transpose()).transpose();
}

// S·K·S of the interior block of K (S the orthonormal DST-I, its own transpose), by mode parity:
// the blocks of the modes 0, 2, 4, … and 1, 3, 5, … (a persymmetric K couples no mode of one
// parity with one of the other: the sine mode k + 1 is symmetric for even k, antisymmetric for odd).
std::array<Eigen::MatrixXd, 2> sine_both_sides(const Eigen::MatrixXd& K) {
  const Eigen::Index k = K.rows() - 2;
  const Eigen::MatrixXd full = sine_2d(K.block(1, 1, k, k));
  std::array<Eigen::MatrixXd, 2> out;
  for (Eigen::Index p = 0; p < 2; ++p) out[std::size_t(p)] = full(Eigen::seq(p, k - 1, 2), Eigen::seq(p, k - 1, 2));
  return out;
}

}  // namespace

SpectralAlphaObjective::Quadratic SpectralAlphaObjective::exact_energies(const ControlNet& coons,
                                                                         const std::vector<EnergyTerm>& exact,
                                                                         const Eigen::MatrixXd (&A)[3],
                                                                         const Eigen::MatrixXd (&B)[3]) const {
  // Σ w·tr(Nᵀ K_a N K_b) per coordinate: ĉ as the outer product of the transformed K_a A and K_b B
  // at the interior, and E(N_C) from the Coons net itself: the factors' 4×4 Gram matrices would
  // lose ε·‖K_a A‖‖K_b B‖ to cancellation (1e-14 where E(N_C) = 0, as for the twist of a bilinear
  // boundary), and this costs no more than one evaluation.
  const int m = rows_ + 1, n = cols_ + 1;
  Quadratic q;
  q.constant = combined_energy(coons, exact);
  for (auto& c_hat : q.c_hat) c_hat = Eigen::MatrixXd::Zero(rows_, cols_);
  for (const EnergyTerm& t : exact) {
    const Eigen::MatrixXd Ka = derivative_gram(m, t.a), Kb = derivative_gram(n, t.b);
    for (int c = 0; c < 3; ++c) {
      const Eigen::MatrixXd KA = Ka * A[c], KB = Kb * B[c];
      q.c_hat[c] += t.weight * solvers::sine_transform_1d(KA.middleRows(1, rows_)) *
                    solvers::sine_transform_1d(KB.middleRows(1, cols_)).transpose();
      q.c_scale += std::abs(t.weight) * KA.norm() * KB.norm();
    }
    q.terms.push_back({sine_both_sides(Ka), sine_both_sides(Kb), t.weight});
  }
  return q;
}

}  // namespace coons
