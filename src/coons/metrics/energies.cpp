#include "energies.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "coons/mask/mask_residual.h"
#include "coons/metrics/scaled_energy.h"
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

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A first-order bound on the rounding error of fl(Δ^order P), given the error `in` of P: every
// subtraction rounds to ε times its result, and ‖Δ^r P‖ ≤ 2^(r−1)‖ΔP‖ (Frobenius norms).
double differences_error(double in, double first_difference_norm, int order) {
  return std::ldexp(in, order) + kEps * order * std::ldexp(first_difference_norm, order - 1);
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
// When X is Y each form is an energy, a sum of squares, that rounding can still take below 0 where
// it is 0 (−5.5e-32 for e3 of a quadratic net): a first-order bound on the rounding of the
// differences, the Gram products (‖G^k‖ ≤ 1/(k+1), its row sum) and the final sum is kept alongside.
struct PairForms {
  std::vector<double> value, rounding;  //!< rounding: 0 unless `energies`
  bool energies = false;                //!< X is Y
};

PairForms pair_forms(const ControlNet& X, const ControlNet& Y, const std::vector<std::pair<int, int>>& pairs,
                     GramCache& gram, int threads = 1) {
  PairForms forms;
  std::vector<double>& out = forms.value;
  std::vector<double>& rounding = forms.rounding;
  out.assign(pairs.size(), 0.0);
  rounding.assign(pairs.size(), 0.0);
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
  const bool same = &X == &Y;
  forms.energies = same;
  if (left_orders.empty()) return forms;
  // a Gram product G^k·D of differences D: the product's error bound given that of D
  auto product_error = [](int k, double differences_error, double differences_norm) {
    return (differences_error + (k + 2) * kEps * differences_norm) / (k + 1);
  };
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd x = coordinate_grid(X, c);
    std::map<int, Eigen::MatrixXd> right;  // Y Δ^bᵀ G^{n−b}
    std::map<int, double> right_error;     // its rounding bound, when X is Y
    {
      const Eigen::MatrixXd y = same ? Eigen::MatrixXd() : coordinate_grid(Y, c);
      const double dx = same && X.n > 0 ? column_differences(x, 1).norm() : 0;
      for (int b : right_orders) {
        const Eigen::MatrixXd d = column_differences(same ? x : y, b);
        right[b] = gram(X.n - b).right(d, threads);
        if (same) right_error[b] = product_error(X.n - b, differences_error(0, dx, b), d.norm());
      }
    }
    const double dx = same && X.m > 0 ? row_differences(x, 1).norm() : 0;
    for (int a : left_orders) {
      const Eigen::MatrixXd d = row_differences(x, a);
      const Eigen::MatrixXd left = gram(X.m - a).left(d, threads);  // G^{m−a} Δ^a X
      const double left_error = same ? product_error(X.m - a, differences_error(0, dx, a), d.norm()) : 0;
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const auto [pa, pb] = pairs[p];
        if (pa != a || pb > X.n) continue;
        const Eigen::MatrixXd l = column_differences(left, pb), r = row_differences(right.at(pb), a);
        out[p] += l.cwiseProduct(r).sum();
        if (!same) continue;
        const double el = differences_error(left_error, 2 * left.norm(), pb);
        const double er = differences_error(right_error.at(pb), 2 * right.at(pb).norm(), a);
        rounding[p] += l.norm() * er + el * r.norm() + el * er + double(l.size() + 1) * kEps * l.norm() * r.norm();
      }
    }
  }
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const double factor = falling_factorial(X.m, pairs[p].first) * falling_factorial(X.n, pairs[p].second);
    out[p] *= factor * factor;
    rounding[p] *= 2 * factor * factor;  // twice the first-order bound: the second-order terms, the factor
  }
  return forms;
}

// Σ weight·value over (index, weight) in this order; an energy (`energies`, every weight ≥ 0: a sum
// of squares) that rounding took below 0 is 0 (clamp_rounding_negative), a clearly negative one stays.
double weighted_forms(const PairForms& f, const std::vector<std::pair<std::size_t, double>>& terms) {
  double sum = 0, magnitude = 0, bound = 0;
  bool nonnegative = f.energies;
  for (const auto& [p, weight] : terms) {
    sum += weight * f.value[p];
    magnitude += std::abs(weight * f.value[p]);
    bound += std::abs(weight) * f.rounding[p];
    nonnegative = nonnegative && weight >= 0;
  }
  return nonnegative ? clamp_rounding_negative(sum, bound + double(terms.size()) * kEps * magnitude) : sum;
}

std::vector<std::pair<int, int>> pairs_of(const std::vector<EnergyTerm>& terms) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(terms.size());
  for (const EnergyTerm& t : terms) pairs.emplace_back(t.a, t.b);
  return pairs;
}

std::vector<std::pair<std::size_t, double>> weights_of(const std::vector<EnergyTerm>& terms) {
  std::vector<std::pair<std::size_t, double>> weights;
  weights.reserve(terms.size());
  for (std::size_t t = 0; t < terms.size(); ++t) weights.emplace_back(t, terms[t].weight);
  return weights;
}

}  // namespace

double clamp_rounding_negative(double value, double rounding_bound) {
  return value < 0 && -value <= rounding_bound ? 0.0 : value;
}

double surface_energy(const ControlNet& net, int a, int b) {
  return scaled_form(net, net, [&](const ControlNet& x, const ControlNet& y) {
    GramCache gram;
    return weighted_forms(pair_forms(x, y, {{a, b}}, gram), {{0, 1.0}});
  });
}

double surface_energy_form(const ControlNet& X, const ControlNet& Y, int a, int b) {
  return scaled_form(X, Y, [&](const ControlNet& x, const ControlNet& y) {
    GramCache gram;
    return pair_forms(x, y, {{a, b}}, gram).value[0];
  });
}

std::vector<EnergyTerm> twist_terms() { return {{1, 1, 1}}; }
std::vector<EnergyTerm> dirichlet_terms() { return {{1, 0, 1}, {0, 1, 1}}; }
std::vector<EnergyTerm> thin_plate_terms() { return {{2, 0, 1}, {1, 1, 2}, {0, 2, 1}}; }
std::vector<EnergyTerm> e3_terms() { return {{3, 0, 1}, {2, 1, 3}, {1, 2, 3}, {0, 3, 1}}; }

double combined_energy(const ControlNet& net, const std::vector<EnergyTerm>& terms) {
  return combined_energy_form(net, net, terms);
}

double combined_energy_form(const ControlNet& X, const ControlNet& Y, const std::vector<EnergyTerm>& terms) {
  return scaled_form(X, Y, [&](const ControlNet& x, const ControlNet& y) {
    GramCache gram;
    return weighted_forms(pair_forms(x, y, pairs_of(terms), gram), weights_of(terms));
  });
}

double twist_energy(const ControlNet& net) { return combined_energy(net, twist_terms()); }
double dirichlet_energy(const ControlNet& net) { return combined_energy(net, dirichlet_terms()); }
double thin_plate_energy(const ControlNet& net) { return combined_energy(net, thin_plate_terms()); }
double e3_energy(const ControlNet& net) { return combined_energy(net, e3_terms()); }

double discrete_twist_energy(const ControlNet& given) {
  return scaled_energy(given, [](const ControlNet& net) {
    double e = 0;
    for (int i = 0; i < net.m; ++i)
      for (int j = 0; j < net.n; ++j)
        e += (net.at(i + 1, j + 1) - net.at(i + 1, j) - net.at(i, j + 1) + net.at(i, j)).squaredNorm();
    return e;
  });
}

double discrete_dirichlet_energy(const ControlNet& given) {
  return scaled_energy(given, [](const ControlNet& net) {
    double e = 0;
    for (int i = 0; i <= net.m; ++i)
      for (int j = 0; j <= net.n; ++j) {
        if (i < net.m) e += (net.at(i + 1, j) - net.at(i, j)).squaredNorm();
        if (j < net.n) e += (net.at(i, j + 1) - net.at(i, j)).squaredNorm();
      }
    return e;
  });
}

namespace {
using GridMap = Eigen::Map<const Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
GridMap grid(const ControlNet& net, int c) { return GridMap(net.points.col(c).data(), net.m + 1, net.n + 1); }
}  // namespace

namespace {
// discrete_energy_form of nets in range (scaled_form).
double discrete_form(const ControlNet& X, const ControlNet& Y, DiscreteEnergy kind) {
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
}  // namespace

double discrete_energy_form(const ControlNet& X, const ControlNet& Y, DiscreteEnergy kind) {
  return scaled_form(X, Y, [kind](const ControlNet& x, const ControlNet& y) { return discrete_form(x, y, kind); });
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

NetMetrics net_energies_in_range(const ControlNet& net, int threads);

// The energies of net_energies_in_range, of a net moved to the centre of its box (they are all of
// differences: a net at 1e12 kept 6 digits of its thin plate) and brought into range
// (scaled_energy.h).
NetMetrics net_energies(const ControlNet& given, int threads) {
  ControlNet net = given;
  net.points.rowwise() -= bounding_box_centre(net.points);
  const int k = energy_scale_exponent(net);
  if (k == 0) return net_energies_in_range(net, threads);
  NetMetrics out = net_energies_in_range(times_power_of_two(net, -k), threads);
  for (double* e : {&out.twist_energy, &out.thin_plate_energy, &out.dirichlet_energy, &out.e3_energy,
                    &out.discrete_twist_energy, &out.discrete_dirichlet_energy})
    *e = std::ldexp(*e, 2 * k);
  return out;
}

NetMetrics net_energies_in_range(const ControlNet& net, int threads) {
  // Every pair of the four energies in one pass (8 Gram products per coordinate).
  const std::vector<std::pair<int, int>> pairs = {{1, 1}, {1, 0}, {0, 1}, {2, 0}, {0, 2},
                                                  {3, 0}, {2, 1}, {1, 2}, {0, 3}};
  GramCache g;
  const PairForms e = pair_forms(net, net, pairs, g, threads);
  NetMetrics out;
  out.twist_energy = weighted_forms(e, {{0, 1.0}});
  out.dirichlet_energy = weighted_forms(e, {{1, 1.0}, {2, 1.0}});
  out.thin_plate_energy = weighted_forms(e, {{3, 1.0}, {0, 2.0}, {4, 1.0}});
  out.e3_energy = weighted_forms(e, {{5, 1.0}, {6, 3.0}, {7, 3.0}, {8, 1.0}});
  out.discrete_twist_energy = discrete_twist_energy(net);
  out.discrete_dirichlet_energy = discrete_dirichlet_energy(net);
  return out;
}

}  // namespace

NetMetrics net_metrics(const ControlNet& net, const Mask9& mask, int threads) {
  NetMetrics out = net_energies(net, threads);
  out.mask_residual = mask_residual(net, mask);
  return out;
}

NetMetrics net_metrics(const ControlNet& net, const FreeGrid& free, const Stencil& stencil, int threads) {
  NetMetrics out = net_energies(net, threads);
  out.mask_residual = mask_residual(net, free, stencil);
  return out;
}

}  // namespace coons
