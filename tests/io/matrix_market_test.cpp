#include "coons/io/matrix_market.h"

#include <catch2/catch.hpp>
#include <filesystem>

#include "coons/io/input_error.h"
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

TEST_CASE("read_matrix_market: sizes, indices and counts are checked before use", "[io]") {
  const TempDir dir;
  const std::string banner = "%%MatrixMarket matrix coordinate real general\n";
  auto error_of = [&](const std::string& body) -> std::string {
    const std::string path = dir.write("A.mtx", banner + body);
    try {
      read_matrix_market(path);
    } catch (const InputError& e) {
      CHECK(e.file() == path);
      return e.field() + ": " + e.reason();
    }
    return "no error";
  };
  CHECK(error_of("2 2 2\n1 1 1\n2 2 3\n") == "no error");
  // a size that would take gigabytes: refused by the size of the file, not by bad_alloc
  CHECK(error_of("2 2 4000000000\n1 1 1\n").find("size line: 4000000000 entries do not fit") == 0);
  CHECK(error_of("99999999999 2 1\n1 1 1\n").find("size line: 99999999999 by 2 is beyond the limit") == 0);
  CHECK(error_of("99999999999999999999 2 1\n1 1 1\n").find("size line: expected 3 integers") == 0);
  CHECK(error_of("2 2 1\n3 1 1\n") == "line 3: entry (3, 1) outside the 2 by 2 matrix");
  CHECK(error_of("2 2 2\n1 1 1\n") == "size line: promises 2 entries, the file holds 1");
  CHECK(error_of("2 2 1\n1 1 1\n2 2 1\n") == "line 4: more entries than the 1 of the size line");
  CHECK(error_of("2 2 1\n1 1 x\n") == "line 3: expected 'row column value'");
}

TEST_CASE("read_dense_matrix_market: the size must fit the file and every value be a finite number", "[io]") {
  const TempDir dir;
  const std::string banner = "%%MatrixMarket matrix array real general\n";
  auto error_of = [&](const std::string& body) -> std::string {
    try {
      read_dense_matrix_market(dir.write("B.mtx", banner + body));
    } catch (const InputError& e) {
      return e.field() + ": " + e.reason();
    }
    return "no error";
  };
  CHECK(error_of("2 1\n1\n2\n") == "no error");
  CHECK(error_of("100000 100000\n1\n").find("size line: a 100000 by 100000 matrix does not fit") == 0);
  CHECK(error_of("2 1\n1\n") == "entry (2, 1): missing");
  CHECK(error_of("2 1\n1\nnan\n") == "entry (2, 1): not a number");
  CHECK(error_of("1 1\n1\n2\n") == "line 4: more values than the size line says");
}
