#include "support/fixtures.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "coons/alpha/objective.h"
#include "coons/net/bernstein.h"

namespace coons::test {

ControlNet make_random_net(int m, int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dist(-1, 1);
  ControlNet net(m, n);
  for (Eigen::Index r = 0; r < net.points.rows(); ++r)
    for (int c = 0; c < 3; ++c) net.points(r, c) = dist(rng);
  return net;
}

Boundary make_random_boundary(int m, int n, std::uint32_t seed) {
  return boundary_of(make_random_net(m, n, seed), "random");
}

Boundary make_smooth_boundary(int m, int n, std::uint32_t seed) {
  // p(u, v) = Σ_{a+b ≤ 3} c_ab u^a v^b with random c (terms above the degree dropped), written
  // exactly as a Bézier net: u^a at degree m has Bernstein coefficients C(i, a)/C(m, a).
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dist(-1, 1);
  double c[4][4][3] = {};
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; a + b <= 3; ++b)
      for (int k = 0; k < 3; ++k) c[a][b][k] = dist(rng);
  c[1][0][0] += 2;  // keep it roughly a graph over the (x, y) plane
  c[0][1][1] += 2;
  auto coef = [](int i, int a, int deg) {  // Bernstein coefficient of t^a at index i
    if (a > deg) return 0.0;
    double num = 1, den = 1;
    for (int r = 0; r < a; ++r) {
      num *= (i - r);
      den *= (deg - r);
    }
    return num / den;
  };
  ControlNet net(m, n);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j)
      for (int k = 0; k < 3; ++k) {
        double v = 0;
        for (int a = 0; a <= 3; ++a)
          for (int b = 0; a + b <= 3; ++b) v += c[a][b][k] * coef(i, a, net.m) * coef(j, b, net.n);
        net.at(i, j)(k) = v;
      }
  return boundary_of(net, "smooth");
}

ControlNet make_bilinear_net(int m, int n, std::uint32_t seed) {
  const ControlNet corners = make_random_net(1, 1, seed);
  ControlNet net(m, n);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = double(i) / m, v = double(j) / n;
      net.at(i, j) = (1 - u) * (1 - v) * corners.at(0, 0) + u * (1 - v) * corners.at(1, 0) +
                     (1 - u) * v * corners.at(0, 1) + u * v * corners.at(1, 1);
    }
  return net;
}

ControlNet transformed(const ControlNet& net, const Eigen::Matrix3d& M, const Eigen::RowVector3d& t) {
  ControlNet out = net;
  out.points = (net.points * M.transpose()).rowwise() + t;
  return out;
}

Boundary transformed(const Boundary& b, const Eigen::Matrix3d& M, const Eigen::RowVector3d& t) {
  Boundary out = b;
  for (Eigen::MatrixX3d* side : {&out.bottom, &out.top, &out.left, &out.right})
    *side = ((*side) * M.transpose()).rowwise() + t;
  return out;
}

ControlNet transposed(const ControlNet& net) {
  ControlNet out(net.n, net.m);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) out.at(j, i) = net.at(i, j);
  return out;
}

ControlNet flipped_u(const ControlNet& net) {
  ControlNet out(net.m, net.n);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) out.at(net.m - i, j) = net.at(i, j);
  return out;
}

double max_difference(const ControlNet& a, const ControlNet& b) { return (a.points - b.points).cwiseAbs().maxCoeff(); }

Eigen::RowVector3d bezier_curve(const Eigen::MatrixX3d& P, double t) {
  const Eigen::VectorXd B = bernstein_basis(int(P.rows()) - 1, t);
  return B.transpose() * P;
}

Eigen::VectorXd bernstein_basis_derivative(int k, int r, double t) {
  // d/dt B_i^k = k (B_{i−1}^{k−1} − B_i^{k−1}), applied r times.
  if (r > k) return Eigen::VectorXd::Zero(k + 1);
  Eigen::VectorXd low = bernstein_basis(k - r, t);  // degree k − r
  for (int level = k - r + 1; level <= k; ++level) {
    Eigen::VectorXd up = Eigen::VectorXd::Zero(level + 1);
    for (int i = 0; i <= level; ++i) {
      const double left = i >= 1 ? low(i - 1) : 0.0, right = i <= level - 1 ? low(i) : 0.0;
      up(i) = level * (left - right);
    }
    low = up;
  }
  return low;
}

TempDir::TempDir() {
  static int counter = 0;
  path = std::filesystem::temp_directory_path() /
         ("coons_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  std::ofstream(path / name) << text;
  return file(name);
}

CommandResult run_command(const std::string& command) {
  char out_name[] = "/tmp/coons_test_out_XXXXXX", err_name[] = "/tmp/coons_test_err_XXXXXX";
  const int out_fd = mkstemp(out_name), err_fd = mkstemp(err_name);
  close(out_fd);
  close(err_fd);
  const std::string full = command + " >" + out_name + " 2>" + err_name + " </dev/null";
  const int raw = std::system(full.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  auto slurp = [](const char* path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  r.out = slurp(out_name);
  r.err = slurp(err_name);
  std::remove(out_name);
  std::remove(err_name);
  return r;
}

Objective objective_named(const std::string& name) {
  std::string why;
  std::optional<Objective> objective = parse_objective(name, &why);
  if (!objective) throw std::invalid_argument("objective '" + name + "': " + why);
  return *std::move(objective);
}

const solvers::SolverInfo& backend(const std::string& name) {
  const solvers::SolverInfo* info = solvers::find_solver(name);
  if (!info) throw std::invalid_argument("no backend named '" + name + "' is built in");
  return *info;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string joined_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& line : lines) s += line + "\n";
  return s;
}

}  // namespace coons::test
