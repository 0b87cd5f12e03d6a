#include <catch2/catch.hpp>

#include <filesystem>

#include "coons/io/matrix_market.h"
#include "coons/mask/assemble_mask_system.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

TEST_CASE("write_matrix_market: the system reads back bit-exactly", "[io]") {
  const auto dir = std::filesystem::temp_directory_path() / "coons_mm_test";
  std::filesystem::create_directories(dir);
  const MaskSystem s = assemble_mask_system(make_random_net(7, 5, 12), alpha_mask(-0.1234567890123));
  const std::string a = (dir / "A.mtx").string(), b = (dir / "B.mtx").string();
  write_matrix_market(a, s.A);
  write_dense_matrix_market(b, s.B);
  const Eigen::SparseMatrix<double> A = read_matrix_market(a);
  const Eigen::MatrixXd B = read_dense_matrix_market(b);
  REQUIRE(A.rows() == s.A.rows());
  REQUIRE(A.nonZeros() == s.A.nonZeros());
  CHECK((Eigen::MatrixXd(A) - Eigen::MatrixXd(s.A)).cwiseAbs().maxCoeff() == 0);
  REQUIRE(B.rows() == s.B.rows());
  CHECK((B - Eigen::MatrixXd(s.B)).cwiseAbs().maxCoeff() == 0);
  CHECK(!std::filesystem::exists(a + ".part"));
  std::filesystem::remove_all(dir);
}
