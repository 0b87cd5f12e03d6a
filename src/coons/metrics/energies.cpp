#include "energies.h"

#include <cmath>
#include <map>

#include "coons/mask/mask_residual.h"
#include "coons/net/bernstein.h"

namespace coons {

namespace {

// Gram matrices are reused across the energies of one net.
class GramCache {
 public:
  const Eigen::MatrixXd& operator()(int k) {
    auto it = cache_.find(k);
    if (it == cache_.end()) it = cache_.emplace(k, bernstein_gram(k)).first;
    return it->second;
  }

 private:
  std::map<int, Eigen::MatrixXd> cache_;
};

double form(const ControlNet& X, const ControlNet& Y, int a, int b, GramCache& gram) {
  if (a > X.m || b > X.n) return 0;
  const ControlNet dx = derivative_net(X, a, b);
  const ControlNet dy = &X == &Y ? dx : derivative_net(Y, a, b);
  const Eigen::MatrixXd& Gu = gram(dx.m);
  const Eigen::MatrixXd& Gv = gram(dx.n);
  double e = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd CX = coordinate_grid(dx, c);
    const Eigen::MatrixXd CY = &X == &Y ? CX : coordinate_grid(dy, c);
    e += ((Gu * CX) * Gv).cwiseProduct(CY).sum();
  }
  return e;
}

double energy(const ControlNet& net, int a, int b, GramCache& gram) { return form(net, net, a, b, gram); }

}  // namespace

double surface_energy(const ControlNet& net, int a, int b) {
  GramCache gram;
  return energy(net, a, b, gram);
}

double surface_energy_form(const ControlNet& X, const ControlNet& Y, int a, int b) {
  GramCache gram;
  return form(X, Y, a, b, gram);
}

std::vector<EnergyTerm> twist_terms() { return {{1, 1, 1}}; }
std::vector<EnergyTerm> dirichlet_terms() { return {{1, 0, 1}, {0, 1, 1}}; }
std::vector<EnergyTerm> thin_plate_terms() { return {{2, 0, 1}, {1, 1, 2}, {0, 2, 1}}; }
std::vector<EnergyTerm> e3_terms() { return {{3, 0, 1}, {2, 1, 3}, {1, 2, 3}, {0, 3, 1}}; }

double combined_energy(const ControlNet& net, const std::vector<EnergyTerm>& terms) {
  GramCache gram;
  double e = 0;
  for (const EnergyTerm& t : terms) e += t.weight * energy(net, t.a, t.b, gram);
  return e;
}

double combined_energy_form(const ControlNet& X, const ControlNet& Y, const std::vector<EnergyTerm>& terms) {
  GramCache gram;
  double e = 0;
  for (const EnergyTerm& t : terms) e += t.weight * form(X, Y, t.a, t.b, gram);
  return e;
}

double twist_energy(const ControlNet& net) { return surface_energy(net, 1, 1); }

double dirichlet_energy(const ControlNet& net) {
  GramCache g;
  return energy(net, 1, 0, g) + energy(net, 0, 1, g);
}

double thin_plate_energy(const ControlNet& net) {
  GramCache g;
  return energy(net, 2, 0, g) + 2 * energy(net, 1, 1, g) + energy(net, 0, 2, g);
}

double e3_energy(const ControlNet& net) {
  GramCache g;
  return energy(net, 3, 0, g) + 3 * energy(net, 2, 1, g) + 3 * energy(net, 1, 2, g) + energy(net, 0, 3, g);
}

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
    auto di = [m, n](const GridMap& g) { return g.bottomRows(m) - g.topRows(m); };
    auto dj = [m, n](const GridMap& g) { return g.rightCols(n) - g.leftCols(n); };
    switch (kind) {
      case DiscreteEnergy::kTwist:
        e += (d11(x) * d11(y)).sum();
        break;
      case DiscreteEnergy::kDirichlet:
        e += (di(x) * di(y)).sum() + (dj(x) * dj(y)).sum();
        break;
      case DiscreteEnergy::kThinPlate:
        if (m >= 2) {
          auto dii = [m, n](const GridMap& g) {
            return g.bottomRows(m - 1) - 2 * g.middleRows(1, m - 1) + g.topRows(m - 1);
          };
          e += (dii(x) * dii(y)).sum();
        }
        if (n >= 2) {
          auto djj = [m, n](const GridMap& g) {
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
  GramCache g;
  NetMetrics out;
  const double e11 = energy(net, 1, 1, g);
  out.twist_energy = e11;
  out.dirichlet_energy = energy(net, 1, 0, g) + energy(net, 0, 1, g);
  out.thin_plate_energy = energy(net, 2, 0, g) + 2 * e11 + energy(net, 0, 2, g);
  out.e3_energy = energy(net, 3, 0, g) + 3 * energy(net, 2, 1, g) + 3 * energy(net, 1, 2, g) + energy(net, 0, 3, g);
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
