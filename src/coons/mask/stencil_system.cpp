#include "stencil_system.h"

#include <algorithm>
#include <cassert>
#include <utility>

#include "solvers/column_fill.h"

namespace coons {

namespace {

// Offsets of the stored pattern: the support of W (centre always), or the whole box.
Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> pattern_of(const Stencil& s, bool box) {
  Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> p = s.weights.array() != 0;
  if (box) p.setConstant(true);
  p(s.radius, s.radius) = true;
  return p;
}

bool inside(const FreeNumbering& f, int i, int j) { return i >= 0 && i <= f.m && j >= 0 && j <= f.n; }

// Calls visit(row, a, b) for the stored entries of column p (free point (i, j)) in index order.
template <class Visit>
void for_each_in_column(const FreeNumbering& f, const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& pattern,
                        int r, int i, int j, Visit&& visit) {
  for (int a = -r; a <= r; ++a)
    for (int b = -r; b <= r; ++b) {
      if (!pattern(r + a, r + b) || !inside(f, i + a, j + b)) continue;
      const int q = f.at(i + a, j + b);
      if (q >= 0) visit(q, a, b);
    }
}

// The stencil on the bounding rectangle of the free points with their free mask (row q of the
// system weighs the point q + d with W(d), as the StencilOperator does).
solvers::StencilOperator grid_operator_of(const Stencil& stencil, const FreeNumbering& f) {
  solvers::StencilOperator op;
  if (f.points.empty()) return op;
  int i0 = f.points.front()[0], i1 = f.points.back()[0], j0 = f.points.front()[1], j1 = j0;
  for (const auto& p : f.points) {
    j0 = std::min(j0, p[1]);
    j1 = std::max(j1, p[1]);
  }
  op.rows = i1 - i0 + 1;
  op.cols = j1 - j0 + 1;
  op.radius = stencil.radius;
  const int r = stencil.radius;
  for (int a = -r; a <= r; ++a)
    for (int b = -r; b <= r; ++b) op.weights.push_back(stencil.at(a, b));
  if (f.points.size() != std::size_t(op.rows) * std::size_t(op.cols)) {
    op.free.assign(std::size_t(op.rows) * std::size_t(op.cols), 0);
    for (const auto& [i, j] : f.points) op.free[std::size_t(i - i0) * std::size_t(op.cols) + std::size_t(j - j0)] = 1;
  }
  return op;
}

void describe_structure(const Stencil& stencil, StencilSystem& system) {
  system.grid.reset();
  system.separable.reset();
  system.grid_operator = grid_operator_of(stencil, system.numbering);
  const auto rect = free_rectangle(system.numbering);
  if (!rect) return;
  if (const auto mask = to_mask9(stencil)) {
    solvers::GridStencil g;
    g.rows = rect->rows();
    g.cols = rect->cols();
    g.center = 1;
    g.edge_i = -mask->edge_i;
    g.edge_j = -mask->edge_j;
    g.diag = -mask->diag;
    system.grid = g;
  }
  if (const auto uv = separable_factors(stencil)) {
    const auto& [u, v] = *uv;
    const int r = stencil.radius;
    solvers::SeparableBandedOperator op;
    op.rows = rect->rows();
    op.cols = rect->cols();
    for (int k = 0; k <= r; ++k) {
      op.along_i[std::size_t(k)] = u(r + k);
      op.along_j[std::size_t(k)] = v(r + k);
    }
    system.separable = op;
  }
}

}  // namespace

FreeNumbering number_free_points(const FreeGrid& free) {
  FreeNumbering f;
  f.m = int(free.rows()) - 1;
  f.n = int(free.cols()) - 1;
  f.unknown.assign(std::size_t(free.rows() * free.cols()), -1);
  for (int i = 0; i <= f.m; ++i)
    for (int j = 0; j <= f.n; ++j)
      if (free(i, j)) {
        f.unknown[std::size_t(i) * (f.n + 1) + j] = f.size();
        f.points.push_back({i, j});
      }
  return f;
}

std::optional<FreeRectangle> free_rectangle(const FreeNumbering& f) {
  if (f.points.empty()) return std::nullopt;
  FreeRectangle r{f.points.front()[0], f.points.back()[0], f.points.front()[1], f.points.front()[1]};
  for (const auto& p : f.points) {
    r.j0 = std::min(r.j0, p[1]);
    r.j1 = std::max(r.j1, p[1]);
  }
  if (std::size_t(r.rows()) * std::size_t(r.cols()) != f.points.size()) return std::nullopt;
  return r;  // as many points as the box holds, all inside it: the box is full
}

StencilSystem assemble_stencil_system(const StencilProblem& problem, const Stencil& stencil,
                                      const StencilAssemblyOptions& options) {
  StencilSystem system;
  system.numbering = number_free_points(free_points(problem));
  system.radius = stencil.radius;
  system.box_pattern = options.box_pattern;
  system.pattern = pattern_of(stencil, options.box_pattern);
  const FreeNumbering& f = system.numbering;
  const int r = stencil.radius;
  if (options.with_matrix) {
    Eigen::Index nnz = 0;
    for (const auto& [i, j] : f.points) for_each_in_column(f, system.pattern, r, i, j, [&](int, int, int) { ++nnz; });
    system.A = solvers::matrix_by_columns(f.size(), nnz, [&](Eigen::Index p, const auto& emit) {
      const auto [i, j] = f.points[std::size_t(p)];
      for_each_in_column(f, system.pattern, r, i, j, [&](int q, int a, int b) {
        emit(q, stencil.at(-a, -b));  // row q's weight of point p = q − (a, b)
      });
    });
  }
  system.B = stencil_rhs(problem.net, f, stencil);
  describe_structure(stencil, system);
  return system;
}

bool refill_stencil_system(const StencilProblem& problem, const Stencil& stencil, StencilSystem& system) {
  if (stencil.radius != system.radius) return false;
  const auto wanted = pattern_of(stencil, false);
  if ((wanted && !system.pattern).any()) return false;
  const FreeNumbering& f = system.numbering;
  if (system.A.nonZeros() > 0) {
    double* value = system.A.valuePtr();
    Eigen::Index pos = 0;
    for (const auto& [i, j] : f.points)
      for_each_in_column(f, system.pattern, stencil.radius, i, j,
                         [&](int, int a, int b) { value[pos++] = stencil.at(-a, -b); });
    assert(pos == system.A.nonZeros());
  }
  system.B = stencil_rhs(problem.net, f, stencil);
  describe_structure(stencil, system);
  return true;
}

Eigen::MatrixX3d stencil_rhs(const ControlNet& net, const FreeNumbering& f, const Stencil& s) {
  Eigen::MatrixX3d B = Eigen::MatrixX3d::Zero(f.size(), 3);
  const int r = s.radius;
  for (int p = 0; p < f.size(); ++p) {
    const auto [i, j] = f.points[std::size_t(p)];
    for (int a = -r; a <= r; ++a)
      for (int b = -r; b <= r; ++b) {
        const double w = s.at(a, b);
        if (w == 0 || !inside(f, i + a, j + b) || f.at(i + a, j + b) >= 0) continue;
        B.row(p) -= w * net.at(i + a, j + b);
      }
  }
  return B;
}

Eigen::MatrixX3d stencil_residual(const ControlNet& net, const FreeNumbering& f, const Stencil& s) {
  Eigen::MatrixX3d Y = Eigen::MatrixX3d::Zero(f.size(), 3);
  const int r = s.radius;
  for (int p = 0; p < f.size(); ++p) {
    const auto [i, j] = f.points[std::size_t(p)];
    for (int a = -r; a <= r; ++a)
      for (int b = -r; b <= r; ++b)
        if (s.at(a, b) != 0 && inside(f, i + a, j + b)) Y.row(p) += s.at(a, b) * net.at(i + a, j + b);
  }
  return Y;
}

Eigen::MatrixX3d stencil_sensitivity_rhs(const ControlNet& solved, const FreeNumbering& f,
                                         const Eigen::MatrixXd& dweights) {
  Stencil d;
  d.radius = int(dweights.rows() / 2);
  d.weights = dweights;
  return -stencil_residual(solved, f, d);
}

ControlNet fill_free_points(ControlNet net, const FreeNumbering& f, const Eigen::MatrixX3d& X) {
  assert(X.rows() == f.size());
  for (int p = 0; p < f.size(); ++p) net.at(f.points[std::size_t(p)][0], f.points[std::size_t(p)][1]) = X.row(p);
  return net;
}

}  // namespace coons
