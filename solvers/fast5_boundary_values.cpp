#include "fast5_boundary_values.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace coons::solvers::fast5_detail {

Eigen::MatrixXd boundary_values(const CapacitanceBlock& blk, int qpar, const Eigen::VectorXd& t, const double* s0,
                                const double* s1, const std::vector<int>& keys, int grid_rows,
                                const std::vector<BoundarySource>& sources) {
  const auto n = Eigen::Index(blk.modes.size()), nq = Eigen::Index(blk.columns.size());
  const auto nk = Eigen::Index(keys.size()), count = Eigen::Index(sources.size());
  const double sign_q = qpar == 0 ? 1.0 : -1.0;  // s_{cols−1−j}(q) = (−1)^q s_j(q)
  const double scale_i = std::sqrt(2.0 / (grid_rows + 1));
  // Gᵀ of [σ̃_e for the key rows e, then β̂⁽⁰⁾, β̂⁽¹⁾ of each right-hand side]
  Eigen::MatrixXd V(n, nk + 2 * count);
  for (Eigen::Index k = 0; k < nk; ++k)
    for (Eigen::Index m = 0; m < n; ++m)
      V(m, k) = scale_i * std::sin(M_PI * double(keys[std::size_t(k)] + 1) * double(blk.modes[std::size_t(m)] + 1) /
                                   double(grid_rows + 1));
  for (Eigen::Index c = 0; c < count; ++c) {
    const Eigen::MatrixXd& beta = sources[std::size_t(c)].beta_hat;
    for (Eigen::Index m = 0; m < n; ++m) {
      const int p = blk.modes[std::size_t(m)];
      V(m, nk + 2 * c) = beta(p, 0) + sign_q * beta(p, 3);
      V(m, nk + 2 * c + 1) = beta(p, 1) + sign_q * beta(p, 2);
    }
  }
  // G of [x_e of each right-hand side and key row e > 0, then z of each right-hand side]: the key
  // row 0 has σ̃_0/σ = 1/√2, so its term is −G(−x_0/√2) and goes into z's product. Row k of that
  // matrix depends on row k of GᵀV only, so both products take one pass over G.
  const bool row0 = nk > 0 && keys[0] == 0;
  const Eigen::Index first = row0 ? 1 : 0, per = nk - first + 1;  // products per right-hand side
  const auto row_of_x = [&](Eigen::Index k, const Eigen::MatrixXd& GtV, Eigen::MatrixXd& X) {
    const int q = blk.columns[std::size_t(k)];
    for (Eigen::Index c = 0; c < count; ++c) {
      const BoundarySource& src = sources[std::size_t(c)];
      double gtf = s0[q] * GtV(k, nk + 2 * c) + s1[q] * GtV(k, nk + 2 * c + 1);  // (Gᵀ F(·, q))_k
      for (Eigen::Index e = 0; e < nk; ++e) gtf += src.rows[std::size_t(e)][q] * GtV(k, e);
      double z = gtf / t[q];
      for (Eigen::Index e = 0; e < nk; ++e) {
        const double x = t[q] * src.rows[std::size_t(e)][q] / blk.c[k];
        if (e < first)
          z -= x * M_SQRT1_2;
        else
          X(k, c * per + e - first) = x;
      }
      X(k, c * per + per - 1) = z;
    }
  };
  Eigen::MatrixXd GtV, X(nq, count * per), GX;
  blk.apply_g_transpose_then_g(V, row_of_x, GtV, X, GX);
  Eigen::MatrixXd out(n, count);
  for (Eigen::Index c = 0; c < count; ++c)
    for (Eigen::Index m = 0; m < n; ++m) {
      double v = V(m, nk + 2 * c) * blk.K(m, 0) + V(m, nk + 2 * c + 1) * blk.K(m, 1) - GX(m, c * per + per - 1);
      for (Eigen::Index e = first; e < nk; ++e) v += V(m, e) / blk.sigma[m] * GX(m, c * per + e - first);
      out(m, c) = v;
    }
  return out;
}

bool boundary_sources(const EdgeRows* edges, int count, detail::SineTransform& along_i, std::size_t max_keys,
                      std::vector<int>& keys, std::array<std::vector<BoundarySource>, 2>& sources) {
  const int rows = along_i.size();
  keys.clear();
  for (int c = 0; c < count; ++c)
    for (int r = 0; r < rows; ++r)
      if (edges[c].slot[std::size_t(r)] >= 0) keys.push_back(std::min(r, rows - 1 - r));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  if (keys.size() > max_keys) return false;
  const double scale_i = std::sqrt(2.0 / (rows + 1));
  Eigen::VectorXd column(rows);
  for (std::size_t ppar = 0; ppar < 2; ++ppar) sources[ppar].resize(std::size_t(count));
  for (int c = 0; c < count; ++c) {
    const EdgeRows& f = edges[c];
    const int cols = f.cols;
    Eigen::MatrixXd beta_hat(rows, 4);
    for (std::size_t j = 0; j < 4; ++j) {
      for (int r = 0; r < rows; ++r) column[r] = f.ends[std::size_t(r)][j];
      along_i.apply(column.data(), beta_hat.col(Eigen::Index(j)).data(), scale_i);
    }
    for (std::size_t ppar = 0; ppar < 2; ++ppar) {
      BoundarySource& src = sources[ppar][std::size_t(c)];
      src.beta_hat = beta_hat;
      src.rows.assign(keys.size(), Eigen::VectorXd::Zero(cols));
      for (int r = 0; r < rows; ++r) {
        const int slot = f.slot[std::size_t(r)];
        if (slot < 0) continue;
        const int key = std::min(r, rows - 1 - r);
        const auto k = std::size_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
        const double sign = (r == key || ppar == 0) ? 1.0 : -1.0;  // σ̃_{rows−1−e} = (−1)^p σ̃_e
        src.rows[k] += sign * Eigen::Map<const Eigen::VectorXd>(f.values.data() + std::ptrdiff_t(slot) * cols, cols);
      }
    }
  }
  return true;
}

}  // namespace coons::solvers::fast5_detail
