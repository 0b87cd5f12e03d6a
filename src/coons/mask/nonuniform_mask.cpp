#include "coons/mask/nonuniform_mask.h"

#include <cmath>
#include <utility>
#include <vector>

#include "coons/mask/near_singular.h"

namespace coons {

namespace {

// The three weights (f_{i−1}, f_i, f_{i+1}) of D f_i = (2/m²) f[x_{i−1}, x_i, x_{i+1}].
Eigen::Vector3d second_difference(const Eigen::VectorXd& x, int i) {
  const int m = int(x.size()) - 1;
  const double before = x(i) - x(i - 1);
  const double after = x(i + 1) - x(i);
  const double scale = 2.0 / (double(m) * m * (before + after));
  const Eigen::Vector3d w(scale / before, 0.0, scale / after);
  return {w(0), -(w(0) + w(2)), w(2)};
}

// ρ for one direction: m (x_{i+1} − x_{i−1}) / 2.
double row_scale(const Eigen::VectorXd& x, int i) { return double(int(x.size()) - 1) * (x(i + 1) - x(i - 1)) / 2.0; }

// The weights of −D_ξ D_η − (D_ξ + D_η), the part of L_α that is multiplied by α; and of
// −(D_ξ + D_η)/4, the part that is not: L_α = α·slope + offset.
void split_weights(const GrevilleGrid& grid, int i, int j, Eigen::Matrix3d& slope, Eigen::Matrix3d& offset) {
  const Eigen::Vector3d a = second_difference(grid.xi, i);
  const Eigen::Vector3d c = second_difference(grid.eta, j);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();  // D_ξ + D_η
  sum.col(1) += a;
  sum.row(1) += c.transpose();
  slope = -(a * c.transpose()) - sum;
  offset = -0.25 * sum;
}

}  // namespace

bool GrevilleGrid::is_valid(std::string* why) const {
  for (const Eigen::VectorXd* x : {&xi, &eta}) {
    const char* name = x == &xi ? "xi" : "eta";
    if (x->size() < 2) {
      if (why) *why = std::string(name) + ": needs at least 2 abscissae";
      return false;
    }
    for (Eigen::Index k = 0; k < x->size(); ++k) {
      if (!std::isfinite((*x)(k)) || (k > 0 && !((*x)(k) > (*x)(k - 1)))) {
        if (why) *why = std::string(name) + ": must be finite and strictly increasing";
        return false;
      }
    }
  }
  return true;
}

Eigen::Matrix3d nonuniform_mask_weights(const GrevilleGrid& grid, double alpha, int i, int j) {
  Eigen::Matrix3d slope, offset;
  split_weights(grid, i, j, slope, offset);
  return alpha * slope + offset;
}

NonUniformMaskSystem assemble_nonuniform_mask_system(const ControlNet& net, const GrevilleGrid& grid, double alpha) {
  const int m = net.m, n = net.n;
  const int rows = std::max(m - 1, 0), cols = std::max(n - 1, 0);
  const Eigen::Index unknowns = Eigen::Index(rows) * cols;
  NonUniformMaskSystem out;
  out.A.resize(unknowns, unknowns);
  out.dA.resize(unknowns, unknowns);
  out.B = Eigen::MatrixX3d::Zero(unknowns, 3);
  out.dB = Eigen::MatrixX3d::Zero(unknowns, 3);
  std::vector<Eigen::Triplet<double>> a_entries, da_entries;
  a_entries.reserve(std::size_t(unknowns) * 9);
  da_entries.reserve(std::size_t(unknowns) * 9);
  const auto unknown = [cols](int i, int j) { return Eigen::Index(i - 1) * cols + (j - 1); };
  for (int i = 1; i < m; ++i)
    for (int j = 1; j < n; ++j) {
      Eigen::Matrix3d slope, offset;
      split_weights(grid, i, j, slope, offset);
      const double rho = row_scale(grid.xi, i) * row_scale(grid.eta, j);
      const Eigen::Index row = unknown(i, j);
      for (int k = -1; k <= 1; ++k)
        for (int l = -1; l <= 1; ++l) {
          const double w_slope = rho * slope(k + 1, l + 1);
          const double w = alpha * w_slope + rho * offset(k + 1, l + 1);
          const int ii = i + k, jj = j + l;
          if (ii > 0 && ii < m && jj > 0 && jj < n) {
            a_entries.emplace_back(row, unknown(ii, jj), w);
            da_entries.emplace_back(row, unknown(ii, jj), w_slope);
          } else {
            out.B.row(row) -= w * net.at(ii, jj);
            out.dB.row(row) -= w_slope * net.at(ii, jj);
          }
        }
    }
  out.A.setFromTriplets(a_entries.begin(), a_entries.end());
  out.dA.setFromTriplets(da_entries.begin(), da_entries.end());
  return out;
}

NonUniformSolveResult solve_nonuniform_mask_net(const ControlNet& frame, const GrevilleGrid& grid, double alpha,
                                                solvers::LinearSolver& solver, bool with_derivative,
                                                double refused_ratio) {
  NonUniformSolveResult out;
  out.net = frame;
  const int rows = std::max(frame.m - 1, 0), cols = std::max(frame.n - 1, 0);
  for (int i = 1; i <= rows; ++i)
    for (int j = 1; j <= cols; ++j) out.net.at(i, j).setZero();
  out.derivative = ControlNet(frame.m, frame.n);
  const NonUniformMaskSystem system = assemble_nonuniform_mask_system(frame, grid, alpha);
  if (system.A.rows() == 0) {
    out.summary.solver = solver.name();
    return out;
  }
  solvers::LinearOperator op;
  op.matrix = &system.A;
  Eigen::MatrixX3d X;
  if (refused_ratio > 0 && !(alpha >= -0.25 && alpha <= 0)) {
    if (solver.analyze(op) != solvers::SolveStatus::kSuccess ||
        solver.factorize(op) != solvers::SolveStatus::kSuccess) {
      out.summary = solver.summary();
      out.summary.relative_residual = system.B.isZero(0) ? 0 : 1;  // not solved: that of X = 0, as solve() says
      return out;
    }
    if (auto refused = near_singular_refusal(system.A, solver, refused_ratio, &out.solves)) {
      out.summary = std::move(*refused);
      if (out.summary.status == solvers::SolveStatus::kSingular)
        out.summary.relative_residual = system.B.isZero(0) ? 0 : 1;  // of X = 0 (near_singular_summary)
      return out;
    }
    out.summary = solver.solve(system.B, X);
  } else {
    out.summary = solver.compute_and_solve(op, system.B, X);
  }
  ++out.solves;
  if (!out.summary.ok()) return out;
  const auto fill = [cols](ControlNet& net, const Eigen::MatrixX3d& values) {
    for (Eigen::Index k = 0; k < values.rows(); ++k) net.at(1 + int(k / cols), 1 + int(k % cols)) = values.row(k);
  };
  fill(out.net, X);
  if (with_derivative) {
    const Eigen::MatrixX3d rhs = system.dB - system.dA * X;
    Eigen::MatrixX3d dX;
    const solvers::SolveSummary second = solver.solve(rhs, dX);
    ++out.solves;
    if (second.ok()) fill(out.derivative, dX);
  }
  return out;
}

double nonuniform_mask_residual(const ControlNet& net, const GrevilleGrid& grid, double alpha) {
  double worst = 0;
  for (int i = 1; i < net.m; ++i)
    for (int j = 1; j < net.n; ++j) {
      // each equation divided by its largest weight: its weights grow like 1/h² on short knot spans
      // (a span of 2e−9 made the residual of a net correct to rounding 25 to 37), and on equal
      // spacing the centre weight 1 is the largest for |α| ≤ 1/2
      const Eigen::Matrix3d w = nonuniform_mask_weights(grid, alpha, i, j);
      const double largest = w.cwiseAbs().maxCoeff();
      if (!(largest > 0)) continue;
      Eigen::RowVector3d r = Eigen::RowVector3d::Zero();
      for (int k = -1; k <= 1; ++k)
        for (int l = -1; l <= 1; ++l) r += (w(k + 1, l + 1) / largest) * net.at(i + k, j + l);
      worst = std::max(worst, r.cwiseAbs().maxCoeff());
    }
  return worst;
}

}  // namespace coons
