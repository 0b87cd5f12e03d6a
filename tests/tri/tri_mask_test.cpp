#include "coons/tri/tri_mask.h"

#include <Eigen/SparseLU>
#include <catch2/catch.hpp>

#include "coons/tri/tri_solve.h"
#include "tri/tri_fixtures.h"

using namespace coons::tri;
using namespace coons::tri_test;

namespace {

// The mask at interior (i, j, k) written out from the contract's formula.
Eigen::RowVector3d mask_by_formula(const TriNet& b, int i, int j, int k, double c) {
  const double a = (1 - 3 * c) / 6;
  return a * (b.at(i + 1, j - 1, k) + b.at(i - 1, j + 1, k) + b.at(i + 1, j, k - 1) + b.at(i - 1, j, k + 1) +
              b.at(i, j + 1, k - 1) + b.at(i, j - 1, k + 1)) +
         c * (b.at(i + 2, j - 1, k - 1) + b.at(i - 1, j + 2, k - 1) + b.at(i - 1, j - 1, k + 2));
}

}  // namespace

TEST_CASE("TriMask: 6a + 3c = 1 and the named members", "[tri]") {
  for (const double c : {-1.0 / 6, 0.0, 0.3, -2.0}) REQUIRE(6 * TriMask{c}.a() + 3 * c == Approx(1));
  REQUIRE(TriMask::quadratic_precision().a() == Approx(0.25));
  REQUIRE(TriMask::laplace().a() == Approx(1.0 / 6));
  std::string why;
  REQUIRE_FALSE(TriMask{std::nan("")}.is_valid(&why));
  REQUIRE(why.find("finite") != std::string::npos);
}

TEST_CASE("assemble_tri_mask_system: A x - B is the mask residual of the contract's formula", "[tri]") {
  for (const int n : {3, 4, 7, 12}) {
    for (const double c : {-1.0 / 6, 0.0, 0.2}) {
      const TriNet net = random_tri_net(n, 500 + n);
      const TriMaskSystem sys = assemble_tri_mask_system(net, TriMask{c});
      REQUIRE(sys.A.rows() == interior_size(n));
      REQUIRE(sys.A.cols() == interior_size(n));
      REQUIRE(sys.A.isCompressed());
      const Eigen::MatrixX3d R = sys.A * interior_of(net) - sys.B;
      double worst = 0;
      for (int k = 1; k <= n - 2; ++k)
        for (int j = 1; j <= n - 1 - k; ++j) {
          const int i = n - k - j;
          const Eigen::RowVector3d expected = net.at(i, j, k) - mask_by_formula(net, i, j, k, c);
          REQUIRE((R.row(interior_index(n, j, k)) - expected).norm() < 1e-13);
          worst = std::max(worst, expected.cwiseAbs().maxCoeff());
        }
      REQUIRE(tri_mask_residual(net, TriMask{c}) == Approx(worst));
      // B depends on the boundary only.
      TriNet other = fill_interior(net, Eigen::MatrixX3d::Random(interior_size(n), 3));
      REQUIRE((assemble_tri_mask_system(other, TriMask{c}).B - sys.B).norm() == 0.0);
    }
  }
}

TEST_CASE("assemble_tri_mask_system: non-symmetric for c != 0, symmetric for c = 0", "[tri]") {
  for (const int n : {5, 9}) {
    const TriNet net = random_tri_net(n, 1);
    const Eigen::SparseMatrix<double> A0 = assemble_tri_mask_system(net, TriMask{0}).A;
    REQUIRE(Eigen::SparseMatrix<double>(A0 - Eigen::SparseMatrix<double>(A0.transpose())).norm() == 0.0);
    for (const double c : {-1.0 / 6, 0.1}) {
      const Eigen::SparseMatrix<double> A = assemble_tri_mask_system(net, TriMask{c}).A;
      const double asym = Eigen::SparseMatrix<double>(A - Eigen::SparseMatrix<double>(A.transpose())).norm();
      REQUIRE(asym > 0.1 * std::abs(c));
    }
  }
}

TEST_CASE("assemble_tri_mask_system: degree < 3 gives an empty system", "[tri]") {
  for (const int n : {0, 1, 2}) {
    const TriMaskSystem sys = assemble_tri_mask_system(random_tri_net(n, 3), TriMask{});
    REQUIRE(sys.A.rows() == 0);
    REQUIRE(sys.B.rows() == 0);
    REQUIRE(tri_mask_residual(random_tri_net(n, 3), TriMask{}) == 0.0);
  }
}

TEST_CASE("interior_of: fill_interior puts the interior back", "[tri]") {
  const TriNet net = random_tri_net(9, 8);
  const TriNet frame = frame_net(boundary_of(net));
  REQUIRE(max_abs_difference(fill_interior(frame, interior_of(net)), net) == 0.0);
}

TEST_CASE("tri_mask_sensitivity_rhs: one extra solve gives the derivative of the interior in c", "[tri]") {
  const TriNet net = random_tri_net(8, 77);
  const double c = -0.1, h = 1e-6;
  auto solve = [&](double cc) {
    TriSolveOptions options;
    options.mask.c = cc;
    return solve_tri_net(boundary_of(net), options).net;
  };
  const TriNet solved = solve(c);
  const TriMaskSystem sys = assemble_tri_mask_system(solved, TriMask{c});
  const Eigen::MatrixX3d dx_dc =
      Eigen::SparseLU<Eigen::SparseMatrix<double>>(sys.A).solve(tri_mask_sensitivity_rhs(solved));
  const Eigen::MatrixX3d fd = (interior_of(solve(c + h)) - interior_of(solve(c - h))) / (2 * h);
  REQUIRE(dx_dc.norm() > 1e-3);
  REQUIRE((dx_dc - fd).cwiseAbs().maxCoeff() < 1e-6 * (1 + fd.cwiseAbs().maxCoeff()));
}
