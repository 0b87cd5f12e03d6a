#include "stencil_problem.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace coons {

namespace {

std::string point_name(int i, int j) { return "(" + std::to_string(i) + ", " + std::to_string(j) + ")"; }
std::string free_field(int i, int j) { return "free[" + std::to_string(i) + "][" + std::to_string(j) + "]"; }

std::string mask_size(const Stencil& s) { return std::to_string(s.size()) + "x" + std::to_string(s.size()); }

using Point = std::pair<int, int>;

// Connected components of the free points under the stencil's non-zero couplings.
std::vector<std::vector<Point>> coupled_components(const FreeGrid& free, const Stencil& s) {
  const int rows = int(free.rows()), cols = int(free.cols()), r = s.radius;
  Eigen::ArrayXXi label = Eigen::ArrayXXi::Constant(rows, cols, -1);
  std::vector<std::vector<Point>> components;
  for (int i0 = 0; i0 < rows; ++i0)
    for (int j0 = 0; j0 < cols; ++j0) {
      if (!free(i0, j0) || label(i0, j0) >= 0) continue;
      const int id = int(components.size());
      components.emplace_back();
      std::vector<Point>& comp = components.back();
      label(i0, j0) = id;
      comp.emplace_back(i0, j0);
      for (std::size_t k = 0; k < comp.size(); ++k) {
        const auto [i, j] = comp[k];
        for (int a = -r; a <= r; ++a)
          for (int b = -r; b <= r; ++b) {
            const int ii = i + a, jj = j + b;
            if ((a == 0 && b == 0) || s.at(a, b) == 0 || ii < 0 || jj < 0 || ii >= rows || jj >= cols) continue;
            if (!free(ii, jj) || label(ii, jj) >= 0) continue;
            label(ii, jj) = id;
            comp.emplace_back(ii, jj);
          }
      }
      std::sort(comp.begin(), comp.end());
    }
  return components;
}

// The mask equations restricted to one component (A(q, p) = W(p − q)).
Eigen::SparseMatrix<double> component_matrix(const std::vector<Point>& comp, const Stencil& s, const FreeGrid& free) {
  Eigen::ArrayXXi local = Eigen::ArrayXXi::Constant(free.rows(), free.cols(), -1);
  for (std::size_t k = 0; k < comp.size(); ++k) local(comp[k].first, comp[k].second) = int(k);
  std::vector<Eigen::Triplet<double>> entries;  // a small check matrix: triplets are fine here
  const int r = s.radius;
  for (std::size_t q = 0; q < comp.size(); ++q) {
    const auto [i, j] = comp[q];
    for (int a = -r; a <= r; ++a)
      for (int b = -r; b <= r; ++b) {
        const int ii = i + a, jj = j + b;
        if (s.at(a, b) == 0 || ii < 0 || jj < 0 || ii >= free.rows() || jj >= free.cols()) continue;
        if (local(ii, jj) >= 0) entries.emplace_back(int(q), local(ii, jj), s.at(a, b));
      }
  }
  Eigen::SparseMatrix<double> A(Eigen::Index(comp.size()), Eigen::Index(comp.size()));
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Smallest |λ| relative to the largest and its vector (dense, symmetric or not).
std::pair<double, Eigen::VectorXd> near_null_dense(const Eigen::MatrixXd& A, bool symmetric) {
  if (symmetric) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
    const Eigen::VectorXd& lambda = eig.eigenvalues();
    Eigen::Index k = 0;
    lambda.cwiseAbs().minCoeff(&k);
    const double top = lambda.cwiseAbs().maxCoeff();
    return {top > 0 ? std::abs(lambda(k)) / top : 0.0, eig.eigenvectors().col(k)};
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const Eigen::Index last = sv.size() - 1;
  return {sv(0) > 0 ? sv(last) / sv(0) : 0.0, svd.matrixV().col(last)};
}

// The same for a large component: sparse LU (shifted when exactly singular) and inverse iteration.
std::pair<double, Eigen::VectorXd> near_null_sparse(const Eigen::SparseMatrix<double>& A) {
  Eigen::SparseMatrix<double> M = A;
  M.makeCompressed();
  double norm = 0;
  for (Eigen::Index c = 0; c < M.outerSize(); ++c) norm = std::max(norm, M.col(c).cwiseAbs().sum());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(M);
  if (lu.info() != Eigen::Success) {
    Eigen::SparseMatrix<double> I(M.rows(), M.cols());
    I.setIdentity();
    M = A + (1e-9 * norm) * I;
    lu.compute(M);
    if (lu.info() != Eigen::Success) return {0.0, Eigen::VectorXd::Ones(A.rows()).normalized()};
  }
  Eigen::VectorXd x(A.rows());
  for (Eigen::Index k = 0; k < x.size(); ++k) x(k) = 1 + 0.5 * std::sin(1.7 * double(k));  // fixed start
  x.normalize();
  for (int it = 0; it < 40; ++it) {
    x = lu.solve(x);
    const double len = x.norm();
    if (!(len > 0) || !std::isfinite(len)) break;
    x /= len;
  }
  const double lambda = (A * x).norm();
  return {norm > 0 ? lambda / norm : 0.0, x};
}

}  // namespace

FreeGrid free_points(const StencilProblem& problem) {
  if (problem.free.size() > 0) return problem.free;
  const int m = problem.net.m, n = problem.net.n, r = std::max(problem.rings, 0);
  FreeGrid free = FreeGrid::Constant(m + 1, n + 1, false);
  for (int i = r; i <= m - r; ++i)
    for (int j = r; j <= n - r; ++j) free(i, j) = true;
  return free;
}

Eigen::RowVector3d data_centre(const StencilProblem& problem, const std::vector<Stencil>& stencils) {
  // the offsets with a non-zero weight in some stencil
  int reach = 0;
  for (const Stencil& s : stencils) reach = std::max(reach, s.radius);
  FreeGrid pattern = FreeGrid::Constant(2 * reach + 1, 2 * reach + 1, false);
  for (const Stencil& s : stencils)
    for (int a = -s.radius; a <= s.radius; ++a)
      for (int b = -s.radius; b <= s.radius; ++b)
        if (s.at(a, b) != 0) pattern(reach + a, reach + b) = true;
  const FreeGrid free = free_points(problem);
  const ControlNet& net = problem.net;
  FreeGrid coupled = FreeGrid::Constant(net.m + 1, net.n + 1, false);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) {
      if (!free(i, j)) continue;
      for (int a = -reach; a <= reach; ++a)
        for (int b = -reach; b <= reach; ++b) {
          const int p = i + a, q = j + b;
          if (p >= 0 && q >= 0 && p <= net.m && q <= net.n && !free(p, q) && pattern(reach + a, reach + b))
            coupled(p, q) = true;
        }
    }
  Eigen::MatrixX3d data(coupled.count(), 3);
  Eigen::Index count = 0;
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j)
      if (coupled(i, j)) data.row(count++) = net.at(i, j);
  return count == 0 ? Eigen::RowVector3d::Zero() : bounding_box_centre(data);
}

StencilProblem rings_problem(ControlNet net, int rings) {
  StencilProblem p;
  p.net = std::move(net);
  p.rings = rings;
  return p;
}

bool ProblemCheckOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (dense_limit < 1) return fail("dense_limit must be >= 1");
  if (!(singular_tolerance > 0 && singular_tolerance < 1)) return fail("singular_tolerance must lie in (0, 1)");
  if (max_named_points < 1) return fail("max_named_points must be >= 1");
  return true;
}

std::vector<ProblemIssue> check_stencil_problem(const StencilProblem& problem, const Stencil& stencil,
                                                const ProblemCheckOptions& options) {
  std::vector<ProblemIssue> issues;
  // the options are the caller's, not the input's: unusable ones are a programming error
  if (std::string why; !options.is_valid(&why)) throw std::invalid_argument("check_stencil_problem: " + why);
  const int m = problem.net.m, n = problem.net.n, r = stencil.radius, rings = problem.rings;
  if (problem.free.size() > 0 && (problem.free.rows() != m + 1 || problem.free.cols() != n + 1)) {
    issues.push_back({"free", -1, -1,
                      "has " + std::to_string(problem.free.rows()) + " rows of " + std::to_string(problem.free.cols()) +
                          " points; the net has " + std::to_string(m + 1) + " rows of " + std::to_string(n + 1)});
    return issues;
  }
  if (rings < 0)
    issues.push_back({"rings", -1, -1, "must be >= 0, got " + std::to_string(rings)});
  else if (rings < r)
    issues.push_back({"rings", -1, -1,
                      std::to_string(rings) + " data ring(s) are too few for a " + mask_size(stencil) +
                          " mask: it needs at least " + std::to_string(r)});
  const FreeGrid free = free_points(problem);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      if (!free(i, j)) continue;
      const int depth = std::min({i, j, m - i, n - j});  // rings outside the point
      if (depth < r)
        issues.push_back(
            {free_field(i, j), i, j, "the " + mask_size(stencil) + " mask at this free point leaves the net"});
    }
  if (!issues.empty() || !options.check_singular) return issues;
  if (symbol_nonnegative(stencil)) return issues;  // every free set is positive definite

  const bool symmetric = symmetry_defect(stencil) == 0;
  for (const auto& comp : coupled_components(free, stencil)) {
    const Eigen::SparseMatrix<double> A = component_matrix(comp, stencil, free);
    const auto [ratio, x] =
        int(comp.size()) <= options.dense_limit ? near_null_dense(Eigen::MatrixXd(A), symmetric) : near_null_sparse(A);
    if (ratio > options.singular_tolerance) continue;
    const double top = x.cwiseAbs().maxCoeff();
    std::vector<Point> named;
    for (std::size_t k = 0; k < comp.size(); ++k)
      if (std::abs(x(Eigen::Index(k))) >= 0.1 * top) named.push_back(comp[k]);
    std::string list;
    for (std::size_t k = 0; k < named.size() && int(k) < options.max_named_points; ++k)
      list += (k ? ", " : "") + point_name(named[k].first, named[k].second);
    if (int(named.size()) > options.max_named_points)
      list += " and " + std::to_string(named.size() - std::size_t(options.max_named_points)) + " more";
    // singular to rounding, not exactly (α = −0.33333333333 beside the singular −1/3 of a 6 × 6
    // net, whose exact solve exists): say how near, as the threshold decides it
    const std::string how = ratio > 0
                                ? fmt::format(
                                      " to within rounding: the smallest eigenvalue or singular value is {:.2g} of the "
                                      "largest, and at most {:.2g} counts as singular",
                                      ratio, options.singular_tolerance)
                                : std::string();
    issues.push_back({free_field(named.front().first, named.front().second), named.front().first, named.front().second,
                      fmt::format("the mask system is singular: the free points {} decouple (they carry a null vector "
                                  "of the equations{})",
                                  list, how)});
  }
  return issues;
}

}  // namespace coons
