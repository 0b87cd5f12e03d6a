#include "coons/io/matrix_market.h"

#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <tuple>
#include <vector>

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
  // (read_market_matrix's checks, behind a banner check of its own)
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
  CHECK(error_of("2 2 4000000000\n1 1 1\n").find("line 2: 4000000000 entries do not fit") == 0);
  CHECK(error_of("99999999999 2 1\n1 1 1\n").find("line 2: 99999999999 by 2 is beyond the limit") == 0);
  CHECK(error_of("99999999999999999999 2 1\n1 1 1\n").find("line 2: expected 3 integers") == 0);
  CHECK(error_of("2 2 1\n3 1 1\n") == "line 3: entry (3, 1) outside the 2 by 2 matrix");
  CHECK(error_of("2 2 2\n1 1 1\n") == "line 2: promises 2 entries, the file holds 1");
  CHECK(error_of("2 2 1\n1 1 1\n2 2 1\n") == "line 4: more entries than the 1 of the size line");
  CHECK(error_of("2 2 1\n1 1 x\n") == "line 3: 'x' is not a decimal number");
  CHECK(error_of("2 2 1\n1 1\n") == "line 3: expected 'row column value'");
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
  CHECK(error_of("100000 100000\n1\n").find("line 2: a 100000 by 100000 matrix does not fit") == 0);
  CHECK(error_of("2 1\n1\n") == "line 2: promises a 2 by 1 general matrix, the file ends at entry (2, 1)");
  CHECK(error_of("2 1\n1\nnan\n") == "line 4: the value 'nan' is not finite");
  CHECK(error_of("1 1\n1\n2\n") == "line 4: more values than the size line says");
}

TEST_CASE("read_matrix_market: each strict reader refuses the other kinds by their banner, zeros included", "[io]") {
  const TempDir dir;
  const std::string symmetric =
      dir.write("S.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 4\n2 1 -1\n");
  const std::string array = dir.write("B.mtx", "%%MatrixMarket  matrix array REAL general\n3 1\n1.5\n0\n-2\n");
  const auto header_error = [](auto read, const std::string& path) -> std::string {
    try {
      read(path);
    } catch (const InputError& e) {
      return e.field() + ": " + e.reason();
    }
    return "no error";
  };
  CHECK(header_error([](const std::string& p) { (void)read_matrix_market(p); }, symmetric) ==
        "header: expected '%%MatrixMarket matrix coordinate real general'");
  CHECK(header_error([](const std::string& p) { (void)read_dense_matrix_market(p); }, symmetric) ==
        "header: expected '%%MatrixMarket matrix array real general'");
  CHECK(read_market_matrix(symmetric).matrix.coeff(0, 1) == -1);  // (the general reader mirrors it)
  // the banner's words in any spacing, but not in another case (the strict readers read what coons writes)
  CHECK(header_error([](const std::string& p) { (void)read_dense_matrix_market(p); }, array) ==
        "header: expected '%%MatrixMarket matrix array real general'");
  const std::string spaced = dir.write("C.mtx", "%%MatrixMarket  matrix array real general\n3 1\n1.5\n0\n-2\n");
  const Eigen::MatrixXd B = read_dense_matrix_market(spaced);
  REQUIRE(B.rows() == 3);
  CHECK(B(0, 0) == 1.5);
  CHECK(B(1, 0) == 0);
  CHECK(B(2, 0) == -2);
  // a −0 (α·0 with α < 0 in a right-hand side) keeps its sign through write and read
  Eigen::MatrixXd signed_zero(2, 1);
  signed_zero << -0.0, 0.0;
  const std::string path = dir.file("Z.mtx");
  write_dense_matrix_market(path, signed_zero);
  const Eigen::MatrixXd Z = read_dense_matrix_market(path);
  CHECK(std::signbit(Z(0, 0)));
  CHECK_FALSE(std::signbit(Z(1, 0)));
}

TEST_CASE("read_market_matrix: a symmetric file equals its expanded general copy", "[io]") {
  const TempDir dir;
  // the bundled SuiteSparse-style file (lower triangle stored) against the general file of its full matrix
  const std::string bundled = std::string(COONS_DATA_DIR) + "/matrices/anisotropic_diffusion.mtx";
  const MarketMatrix symmetric = read_market_matrix(bundled);
  CHECK(symmetric.symmetry == "symmetric");
  const Eigen::SparseMatrix<double>& S = symmetric.matrix;
  REQUIRE(S.rows() == 1024);
  CHECK(S.nonZeros() == 2 * 3008 - 1024);  // off-diagonal entries mirrored, the diagonal once
  CHECK(symmetric.file_entries == 3008);   // the size line's count: one triangle
  const std::string general = dir.file("general.mtx");
  write_matrix_market(general, S);
  const Eigen::SparseMatrix<double> G = read_matrix_market(general);
  CHECK(read_market_matrix(general).symmetry == "general");
  CHECK((Eigen::MatrixXd(S) - Eigen::MatrixXd(G)).cwiseAbs().maxCoeff() == 0);
  CHECK((Eigen::MatrixXd(S) - Eigen::MatrixXd(S.transpose())).cwiseAbs().maxCoeff() == 0);

  // the same small matrix in every form the reader takes
  Eigen::MatrixXd full(3, 3);
  full << 4, -1, 0, -1, 4, -2, 0, -2, 5;
  // (qualifiers, body, the values the file lists)
  const std::vector<std::tuple<std::string, std::string, long long>> forms = {
      {"coordinate real general", "3 3 7\n1 1 4\n2 1 -1\n1 2 -1\n2 2 4\n3 2 -2\n2 3 -2\n3 3 5\n", 7},
      {"coordinate real symmetric", "3 3 5\n1 1 4\n2 1 -1\n2 2 4\n3 2 -2\n3 3 5\n", 5},
      {"coordinate integer symmetric", "3 3 5\n1 1 4\n2 1 -1\n2 2 4\n3 2 -2\n3 3 5\n", 5},
      {"array real general", "3 3\n4\n-1\n0\n-1\n4\n-2\n0\n-2\n5\n", 9},
      {"array real symmetric", "3 3\n4\n-1\n0\n4\n-2\n5\n", 6},
      {"  coordinate   REAL symmetric", "% a comment\n\n3 3 5\n1 1 4\n2 1 -1\n2 2 4\n3 2 -2\n3 3 5\n", 5},
  };
  for (const auto& [qualifiers, body, listed] : forms) {
    INFO(qualifiers);
    std::string text = "%%MatrixMarket matrix " + qualifiers + "\n";
    text += body;
    const MarketMatrix m = read_market_matrix(dir.write("m.mtx", text));
    REQUIRE(m.matrix.rows() == 3);
    CHECK((Eigen::MatrixXd(m.matrix) - full).cwiseAbs().maxCoeff() == 0);
    CHECK(m.file_entries == listed);
  }
  const MarketMatrix pattern =
      read_market_matrix(dir.write("p.mtx", "%%MatrixMarket matrix coordinate pattern general\n2 3 2\n1 1\n2 3\n"));
  CHECK(Eigen::MatrixXd(pattern.matrix) == (Eigen::MatrixXd(2, 3) << 1, 0, 0, 0, 0, 1).finished());
  const MarketMatrix skew =
      read_market_matrix(dir.write("s.mtx", "%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 3\n"));
  CHECK(Eigen::MatrixXd(skew.matrix) == (Eigen::MatrixXd(2, 2) << 0, -3, 3, 0).finished());
  const MarketMatrix columns = read_market_matrix(std::string(COONS_DATA_DIR) + "/matrices/convection_diffusion_b.mtx");
  CHECK(columns.matrix.rows() == 576);
  CHECK(columns.matrix.cols() == 2);
}

TEST_CASE("read_market_matrix: a bad file names its line and the reason", "[io]") {
  const TempDir dir;
  auto error_of = [&](const std::string& text) -> std::string {
    const std::string path = dir.write("bad.mtx", text);
    try {
      read_market_matrix(path);
    } catch (const InputError& e) {
      CHECK(e.file() == path);
      return e.field() + ": " + e.reason();
    }
    return "no error";
  };
  const std::string coordinate = "%%MatrixMarket matrix coordinate real general\n";
  const std::string symmetric = "%%MatrixMarket matrix coordinate real symmetric\n";
  CHECK(error_of(coordinate + "2 2 1\n1 1 1\n") == "no error");
  CHECK(error_of("%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n") ==
        "line 1: complex matrices are not supported (real systems only)");
  CHECK(error_of("%%MatrixMarket tensor coordinate real general\n").find("line 1: expected '%%MatrixMarket") == 0);
  CHECK(error_of("%%MatrixMarket matrix array pattern general\n") ==
        "line 1: a pattern matrix needs the coordinate format");
  CHECK(error_of(coordinate + "% c\n2 x 1\n").find("line 3: expected 3 integers") == 0);
  CHECK(error_of(coordinate + "2 2\n").find("line 2: expected 3 integers") == 0);
  CHECK(error_of(symmetric + "2 3 1\n1 1 1\n") == "line 2: a symmetric matrix must be square, not 2 by 3");
  CHECK(error_of(coordinate + "2 2 1\n3 1 1\n") == "line 3: entry (3, 1) outside the 2 by 2 matrix");
  CHECK(error_of(coordinate + "2 2 1\n0 1 1\n") == "line 3: entry (0, 1) outside the 2 by 2 matrix");
  CHECK(error_of(coordinate + "2 2 1\n1 1 1e999\n") == "line 3: the value '1e999' is not finite");
  CHECK(error_of(coordinate + "2 2 1\n1 1 nan\n") == "line 3: the value 'nan' is not finite");
  CHECK(error_of(coordinate + "2 2 1\n1 1 x\n") == "line 3: 'x' is not a decimal number");
  CHECK(error_of(coordinate + "2 2 1\n1 1 0x10\n") == "line 3: '0x10' is not a decimal number");  // strtod read 16
  CHECK(error_of(coordinate + "2 2 1\n1 1\n") == "line 3: expected 'row column value'");
  CHECK(error_of(coordinate + "2 2 2\n1 1 1\n") == "line 2: promises 2 entries, the file holds 1");
  CHECK(error_of(coordinate + "2 2 1\n1 1 1\n2 2 1\n") == "line 4: more entries than the 1 of the size line");
  CHECK(error_of(symmetric + "2 2 1\n1 2 1\n") ==
        "line 3: entry (1, 2) above the diagonal: a symmetric file stores the lower triangle");
  CHECK(error_of("%%MatrixMarket matrix coordinate integer general\n1 1 1\n1 1 1.5\n") ==
        "line 3: '1.5' is not an integer");
  CHECK(error_of("%%MatrixMarket matrix array real general\n2 1\n1\n") ==
        "line 2: promises a 2 by 1 general matrix, the file ends at entry (2, 1)");
  CHECK(error_of("%%MatrixMarket matrix array real general\n1 1\n1\n2\n") ==
        "line 4: more values than the size line says");
  // a NUL byte ended a token where it stood ("3\0junk" read as 3), and a value below the smallest
  // double read as an explicit 0 where one above the largest is refused; a subnormal value is read
  CHECK(error_of(coordinate + "2 2 1\n1 1 3" + std::string(1, '\0') + "junk\n") ==
        "line 3: '3\\0junk' is not a decimal number");
  CHECK(error_of(coordinate + "2 2 1\n2" + std::string(1, '\0') + "9 1 1\n").find("line 3: expected") == 0);
  // and in the banner or the size line a NUL byte cut the error line short where it was printed
  // ("unknown symmetry 'general", the reason lost; "unexpected '")
  const std::string nul(1, '\0');
  CHECK(error_of("%%MatrixMarket matrix coordinate real general" + nul + "junk\n2 2 1\n1 1 1\n")
            .find("line 1: unknown symmetry 'general\\0junk' (expected") == 0);
  CHECK(error_of(coordinate + "2 2 1" + nul + "\n1 1 1\n") == "line 2: unexpected '\\0' after 3 integers");
  CHECK(error_of(coordinate + "2 2 1\n1 1 1e-400\n") ==
        "line 3: the value '1e-400' is below the smallest double (it would be read as 0)");
  CHECK(error_of(coordinate + "2 2 1\n1 1 1e-320\n") == "no error");
}

TEST_CASE("read_market_matrix: a file that is not Matrix Market is refused by its first line, whatever its size",
          "[io][bad-input]") {
  // A sparse file of 1 GiB + 1 byte (no disk used) past a first line that is no banner: the
  // banner is checked on the first chunk, so the error is the header's, not the byte limit's
  // (which, read whole, it met after reading a gigabyte).
  const TempDir dir;
  const std::string path = dir.write("big.bin", "not a matrix\n");
  std::filesystem::resize_file(path, (std::uintmax_t{1} << 30) + 1);
  auto error_of = [&](auto read) -> std::string {
    try {
      read(path);
    } catch (const InputError& e) {
      return e.field() + ": " + e.reason();
    }
    return "no error";
  };
  CHECK(error_of([](const std::string& p) { read_market_matrix(p); }).find("line 1: expected '%%MatrixMarket") == 0);
  CHECK(error_of([](const std::string& p) { read_matrix_market(p); }) ==
        "header: expected '%%MatrixMarket matrix coordinate real general'");
  CHECK(error_of([](const std::string& p) { read_dense_matrix_market(p); }) ==
        "header: expected '%%MatrixMarket matrix array real general'");
}

TEST_CASE("read_market_matrix: an integer beyond 64 bits is bad input naming its line, not clamped", "[io]") {
  const TempDir dir;
  const std::string integer = "%%MatrixMarket matrix coordinate integer general\n2 2 1\n";
  for (const std::string value : {"99999999999999999999", "-99999999999999999999"}) {
    const std::string path = dir.write("big.mtx", fmt::format("{}1 1 {}\n", integer, value));
    try {
      read_market_matrix(path);
      FAIL("no error for " << value);
    } catch (const InputError& e) {
      CHECK(e.field() == "line 3");
      CHECK(e.reason() == "the integer '" + value + "' is beyond the 64-bit range");
    }
  }
  // the largest one reads (as the nearest double), and a subnormal real is read as one (a real
  // below the smallest double is bad input: read_market_matrix: a bad file names its line and the reason)
  CHECK(read_market_matrix(dir.write("max.mtx", integer + "1 1 9223372036854775807\n")).matrix.coeff(0, 0) == 0x1p63);
  CHECK(read_market_matrix(dir.write("tiny.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1e-320\n"))
            .matrix.coeff(0, 0) == 1e-320);
}

TEST_CASE("read_market_matrix: entries in any order with duplicates give setFromTriplets' matrix bit for bit", "[io]") {
  // the readers compress the entries themselves (O(entries), not O(rows)); duplicates are summed
  // in file order, as Eigen's setFromTriplets sums them
  const TempDir dir;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> row(0, 60), col(0, 6);  // 300 entries of 427 places: duplicates
  std::uniform_real_distribution<double> value(-1, 1);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(300);
  for (int k = 0; k < 300; ++k) entries.emplace_back(row(rng), col(rng), value(rng));
  for (const char* reader : {"read_matrix_market", "read_market_matrix"}) {
    std::string text = "%%MatrixMarket matrix coordinate real general\n61 7 300\n";
    for (const auto& e : entries) text += fmt::format("{} {} {:.17g}\n", e.row() + 1, e.col() + 1, e.value());
    const std::string path = dir.write("A.mtx", text);
    const Eigen::SparseMatrix<double> A =
        std::string(reader) == "read_matrix_market" ? read_matrix_market(path) : read_market_matrix(path).matrix;
    Eigen::SparseMatrix<double> reference(61, 7);
    reference.setFromTriplets(entries.begin(), entries.end());
    INFO(reader);
    REQUIRE(A.isCompressed());
    REQUIRE(A.nonZeros() == reference.nonZeros());
    CHECK(std::equal(A.outerIndexPtr(), A.outerIndexPtr() + 8, reference.outerIndexPtr()));
    CHECK(std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), reference.innerIndexPtr()));
    CHECK(std::equal(A.valuePtr(), A.valuePtr() + A.nonZeros(), reference.valuePtr()));
  }
  // a tall matrix of one entry (the fuzzer's 49,672,948 rows took 12 s through setFromTriplets)
  const std::string tall = dir.write("T.mtx", "%%MatrixMarket matrix coordinate real general\n49672948 2 1\n3 1 1\n");
  const Eigen::SparseMatrix<double> T = read_matrix_market(tall);
  CHECK(T.rows() == 49672948);
  CHECK(T.nonZeros() == 1);
  CHECK(T.coeff(2, 0) == 1);
}

TEST_CASE("read_market_matrix: duplicates that sum beyond the doubles are bad input naming the entry", "[io]") {
  // each value is finite, their sum is not: the matrix would carry inf into every backend, and
  // bench-matrix then blamed the solvers (exit 3) for bad input
  const TempDir dir;
  const std::string path = dir.write(
      "dup.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 4\n1 1 1\n2 1 1e308\n2 2 1\n2 1 1e308\n");
  try {
    read_market_matrix(path);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "entry (2, 1)");
    CHECK_THAT(e.reason(), Catch::Contains("sum to inf"));
  }
  // duplicates that cancel, or more duplicates than the matrix has cells, are a matrix
  const MarketMatrix m = read_market_matrix(
      dir.write("many.mtx", "%%MatrixMarket matrix coordinate real general\n1 1 3\n1 1 1e308\n1 1 -1e308\n1 1 2\n"));
  CHECK(m.matrix.coeff(0, 0) == 2);
}

TEST_CASE("read_market_matrix: check_sizes sees the declared sizes before any entry is read or allocated", "[io]") {
  // 72 bytes declaring 2^26 columns: bench-matrix took 560 MB for them before --max-memory refused
  const TempDir dir;
  const std::string path =
      dir.write("wide.mtx", "%%MatrixMarket matrix coordinate real symmetric\n67108864 67108864 1\nnot an entry\n");
  std::vector<long long> seen;
  const auto refuse = [&](long long rows, long long cols, long long stored, int line) {
    seen = {rows, cols, stored, line};
    throw InputError(path, fmt::format("line {}", line), "too large");
  };
  try {
    read_market_matrix(path, refuse);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.reason() == "too large");  // not the entry's error: the check came first
  }
  CHECK(seen == std::vector<long long>{67108864, 67108864, 2, 2});  // a symmetric entry is stored twice
  // the estimate counts the column pointers of the declared width
  CHECK(market_matrix_bytes(67108864, 2) > 4.0 * 67108864);
}
