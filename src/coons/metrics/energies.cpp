#include "energies.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "coons/mask/mask_residual.h"
#include "coons/net/banded_gram.h"
#include "coons/net/bernstein.h"

namespace coons {

namespace {

// Banded Gram matrices, reused across the energies of one net.
class GramCache {
 public:
  const BandedGram& operator()(int k) {
    auto it = cache_.find(k);
    if (it == cache_.end()) it = cache_.emplace(k, BandedGram(k)).first;
    return it->second;
  }

 private:
  std::map<int, BandedGram> cache_;
};

Eigen::MatrixXd row_differences(Eigen::MatrixXd P, int order) {  // Δ^order along the rows (index i)
  for (int r = 0; r < order; ++r) P = (P.bottomRows(P.rows() - 1) - P.topRows(P.rows() - 1)).eval();
  return P;
}

Eigen::MatrixXd column_differences(Eigen::MatrixXd P, int order) {  // Δ^order along the columns (index j)
  for (int r = 0; r < order; ++r) P = (P.rightCols(P.cols() - 1) - P.leftCols(P.cols() - 1)).eval();
  return P;
}

double falling_factorial(int k, int order) {
  double f = 1;
  for (int r = 0; r < order; ++r) f *= k - r;
  return f;
}

// form(X, Y; a, b) = Σ_xyz tr(C_Xᵀ G^{m−a} C_Y G^{n−b}) with C = [m!/(m−a)!][n!/(n−b)!] Δ^a X Δ^bᵀ for
// every pair at once. The differences of one direction commute with the Gram matrix of the other:
//   tr(C_Xᵀ G_u C_Y G_v) ∝ ⟨(G^{m−a} Δ^a X) Δ^bᵀ, Δ^a (Y Δ^bᵀ G^{n−b})⟩,
// so one product per order a (left) and one per order b (right) serve every pair: 8 banded
// products for the 9 pairs of net_metrics instead of 18 dense ones, and the differences are taken
// before each product, as the derivative nets would be.
std::vector<double> pair_forms(const ControlNet& X, const ControlNet& Y, const std::vector<std::pair<int, int>>& pairs,
                               GramCache& gram) {
  std::vector<double> out(pairs.size(), 0.0);
  std::vector<int> left_orders, right_orders;
  for (const auto& [a, b] : pairs)
    if (a <= X.m && b <= X.n) {
      left_orders.push_back(a);
      right_orders.push_back(b);
    }
  for (std::vector<int>* orders : {&left_orders, &right_orders}) {
    std::sort(orders->begin(), orders->end());
    orders->erase(std::unique(orders->begin(), orders->end()), orders->end());
  }
  if (left_orders.empty()) return out;
  const bool same = &X == &Y;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd x = coordinate_grid(X, c);
    std::map<int, Eigen::MatrixXd> right;  // Y Δ^bᵀ G^{n−b}
    {
      const Eigen::MatrixXd y = same ? Eigen::MatrixXd() : coordinate_grid(Y, c);
      for (int b : right_orders) right[b] = gram(X.n - b).right(column_differences(same ? x : y, b));
    }
    for (int a : left_orders) {
      const Eigen::MatrixXd left = gram(X.m - a).left(row_differences(x, a));  // G^{m−a} Δ^a X
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const auto [pa, pb] = pairs[p];
        if (pa != a || pb > X.n) continue;
        out[p] += column_differences(left, pb).cwiseProduct(row_differences(right.at(pb), a)).sum();
      }
    }
  }
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const double factor = falling_factorial(X.m, pairs[p].first) * falling_factorial(X.n, pairs[p].second);
    out[p] *= factor * factor;
  }
  return out;
}

std::vector<std::pair<int, int>> pairs_of(const std::vector<EnergyTerm>& terms) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(terms.size());
  for (const EnergyTerm& t : terms) pairs.emplace_back(t.a, t.b);
  return pairs;
}

double weighted_sum(const std::vector<EnergyTerm>& terms, const std::vector<double>& values) {
  double e = 0;
  for (std::size_t t = 0; t < terms.size(); ++t) e += terms[t].weight * values[t];
  return e;
}

}  // namespace

double surface_energy(const ControlNet& net, int a, int b) {
  GramCache gram;
  return pair_forms(net, net, {{a, b}}, gram)[0];
}

double surface_energy_form(const ControlNet& X, const ControlNet& Y, int a, int b) {
  GramCache gram;
  return pair_forms(X, Y, {{a, b}}, gram)[0];
}

std::vector<EnergyTerm> twist_terms() { return {{1, 1, 1}}; }
std::vector<EnergyTerm> dirichlet_terms() { return {{1, 0, 1}, {0, 1, 1}}; }
std::vector<EnergyTerm> thin_plate_terms() { return {{2, 0, 1}, {1, 1, 2}, {0, 2, 1}}; }
std::vector<EnergyTerm> e3_terms() { return {{3, 0, 1}, {2, 1, 3}, {1, 2, 3}, {0, 3, 1}}; }

double combined_energy(const ControlNet& net, const std::vector<EnergyTerm>& terms) {
  return combined_energy_form(net, net, terms);
}

double combined_energy_form(const ControlNet& X, const ControlNet& Y, const std::vector<EnergyTerm>& terms) {
  GramCache gram;
  return weighted_sum(terms, pair_forms(X, Y, pairs_of(terms), gram));
}

double twist_energy(const ControlNet& net) { return combined_energy(net, twist_terms()); }
double dirichlet_energy(const ControlNet& net) { return combined_energy(net, dirichlet_terms()); }
double thin_plate_energy(const ControlNet& net) { return combined_energy(net, thin_plate_terms()); }
double e3_energy(const ControlNet& net) { return combined_energy(net, e3_terms()); }

double discrete_twist_energy(const ControlNet& net) {
  double e = 0;
  for (int i = 0; i < net.m; ++i)
    for (int j = 0; j < net.n; ++j)
      e += (net.at(i + 1, j + 1) - net.at(i + 1, j) - net.at(i, j + 1) + net.at(i, j)).squaredNorm();
  return e;
}

double discrete_dirichlet_energy(const ControlNet& net) {
  double e = 0;
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) {
      if (i < net.m) e += (net.at(i + 1, j) - net.at(i, j)).squaredNorm();
      if (j < net.n) e += (net.at(i, j + 1) - net.at(i, j)).squaredNorm();
    }
  return e;
}

namespace {
using GridMap = Eigen::Map<const Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
GridMap grid(const ControlNet& net, int c) { return GridMap(net.points.col(c).data(), net.m + 1, net.n + 1); }
}  // namespace

double discrete_energy_form(const ControlNet& X, const ControlNet& Y, DiscreteEnergy kind) {
  // Whole-grid differences per coordinate (vectorised; O(mn)).
  const Eigen::Index m = X.m, n = X.n;
  double e = 0;
  for (int c = 0; c < 3; ++c) {
    const GridMap x = grid(X, c), y = grid(Y, c);
    auto d11 = [m, n](const GridMap& g) {
      return g.bottomRightCorner(m, n) - g.bottomLeftCorner(m, n) - g.topRightCorner(m, n) + g.topLeftCorner(m, n);
    };
    auto di = [m](const GridMap& g) { return g.bottomRows(m) - g.topRows(m); };
    auto dj = [n](const GridMap& g) { return g.rightCols(n) - g.leftCols(n); };
    switch (kind) {
      case DiscreteEnergy::kTwist:
        e += (d11(x) * d11(y)).sum();
        break;
      case DiscreteEnergy::kDirichlet:
        e += (di(x) * di(y)).sum() + (dj(x) * dj(y)).sum();
        break;
      case DiscreteEnergy::kThinPlate:
        if (m >= 2) {
          auto dii = [m](const GridMap& g) {
            return g.bottomRows(m - 1) - 2 * g.middleRows(1, m - 1) + g.topRows(m - 1);
          };
          e += (dii(x) * dii(y)).sum();
        }
        if (n >= 2) {
          auto djj = [n](const GridMap& g) {
            return g.rightCols(n - 1) - 2 * g.middleCols(1, n - 1) + g.leftCols(n - 1);
          };
          e += (djj(x) * djj(y)).sum();
        }
        e += 2 * (d11(x) * d11(y)).sum();
        break;
    }
  }
  return e;
}

std::vector<DifferenceTerm> difference_terms(DiscreteEnergy kind) {
  switch (kind) {
    case DiscreteEnergy::kTwist:
      return {{1, 1, 1}};
    case DiscreteEnergy::kDirichlet:
      return {{1, 0, 1}, {0, 1, 1}};
    case DiscreteEnergy::kThinPlate:
      return {{2, 0, 1}, {1, 1, 2}, {0, 2, 1}};
  }
  return {};
}

ControlNet discrete_energy_gradient(const ControlNet& net, DiscreteEnergy kind) {
  // E = Σ (D b)² over linear differences D, so ∂E/∂b = 2 Dᵀ(D b): scatter each difference back.
  using RowArray = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;  // as the grids
  using Grid = Eigen::Map<RowArray>;
  const Eigen::Index m = net.m, n = net.n;
  ControlNet g(net.m, net.n);
  for (int c = 0; c < 3; ++c) {
    const GridMap b = grid(net, c);
    Grid out(g.points.col(c).data(), m + 1, n + 1);
    auto add_twist = [&](double weight) {
      const RowArray r =
          2 * weight *
          (b.bottomRightCorner(m, n) - b.bottomLeftCorner(m, n) - b.topRightCorner(m, n) + b.topLeftCorner(m, n));
      out.bottomRightCorner(m, n) += r;
      out.bottomLeftCorner(m, n) -= r;
      out.topRightCorner(m, n) -= r;
      out.topLeftCorner(m, n) += r;
    };
    switch (kind) {
      case DiscreteEnergy::kTwist:
        add_twist(1);
        break;
      case DiscreteEnergy::kDirichlet: {
        const RowArray di = 2 * (b.bottomRows(m) - b.topRows(m));
        out.bottomRows(m) += di;
        out.topRows(m) -= di;
        const RowArray dj = 2 * (b.rightCols(n) - b.leftCols(n));
        out.rightCols(n) += dj;
        out.leftCols(n) -= dj;
        break;
      }
      case DiscreteEnergy::kThinPlate: {
        if (m >= 2) {
          const RowArray dii = 2 * (b.bottomRows(m - 1) - 2 * b.middleRows(1, m - 1) + b.topRows(m - 1));
          out.bottomRows(m - 1) += dii;
          out.middleRows(1, m - 1) -= 2 * dii;
          out.topRows(m - 1) += dii;
        }
        if (n >= 2) {
          const RowArray djj = 2 * (b.rightCols(n - 1) - 2 * b.middleCols(1, n - 1) + b.leftCols(n - 1));
          out.rightCols(n - 1) += djj;
          out.middleCols(1, n - 1) -= 2 * djj;
          out.leftCols(n - 1) += djj;
        }
        add_twist(2);
        break;
      }
    }
  }
  return g;
}

double discrete_thin_plate_energy(const ControlNet& net) {
  return discrete_energy_form(net, net, DiscreteEnergy::kThinPlate);
}

namespace {

NetMetrics net_energies(const ControlNet& net) {
  // Every pair of the four energies in one pass (8 Gram products).
  const std::vector<std::pair<int, int>> pairs = {{1, 1}, {1, 0}, {0, 1}, {2, 0}, {0, 2},
                                                  {3, 0}, {2, 1}, {1, 2}, {0, 3}};
  GramCache g;
  const std::vector<double> e = pair_forms(net, net, pairs, g);
  NetMetrics out;
  out.twist_energy = e[0];
  out.dirichlet_energy = e[1] + e[2];
  out.thin_plate_energy = e[3] + 2 * e[0] + e[4];
  out.e3_energy = e[5] + 3 * e[6] + 3 * e[7] + e[8];
  out.discrete_twist_energy = discrete_twist_energy(net);
  out.discrete_dirichlet_energy = discrete_dirichlet_energy(net);
  return out;
}

}  // namespace

NetMetrics net_metrics(const ControlNet& net, const Mask9& mask) {
  NetMetrics out = net_energies(net);
  out.mask_residual = mask_residual(net, mask);
  return out;
}

NetMetrics net_metrics(const ControlNet& net, const FreeGrid& free, const Stencil& stencil) {
  NetMetrics out = net_energies(net);
  out.mask_residual = mask_residual(net, free, stencil);
  return out;
}

}  // namespace coons
