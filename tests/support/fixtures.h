// Test fixtures made in code: boundaries and nets with fixed seeds.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "coons/net/control_net.h"
#include "solvers/registry.h"

namespace coons {
struct Objective;  // coons/alpha/objective.h
}  // namespace coons

namespace coons::test {

//! A net with uniformly random points in [−1, 1]³ (fixed seed).
ControlNet make_random_net(int m, int n, std::uint32_t seed);

//! The boundary of a random net: corners agree exactly.
Boundary make_random_boundary(int m, int n, std::uint32_t seed);

//! A smooth random boundary: the frame of a random low-degree polynomial surface, elevated.
Boundary make_smooth_boundary(int m, int n, std::uint32_t seed);

//! The net of the bilinear interpolant of four random corners (every 3×3 affine mask reproduces it).
ControlNet make_bilinear_net(int m, int n, std::uint32_t seed);

//! Apply x ↦ M x + t to every point.
ControlNet transformed(const ControlNet& net, const Eigen::Matrix3d& M, const Eigen::RowVector3d& t);
Boundary transformed(const Boundary& b, const Eigen::Matrix3d& M, const Eigen::RowVector3d& t);

//! b'[i][j] = b[j][i].
ControlNet transposed(const ControlNet& net);
//! b'[i][j] = b[m−i][j].
ControlNet flipped_u(const ControlNet& net);

//! max |a − b| over all coordinates; nets must have the same degree.
double max_difference(const ControlNet& a, const ControlNet& b);

//! The surface degree-k Bézier curve with control points P (#k+1 by 3) at t.
Eigen::RowVector3d bezier_curve(const Eigen::MatrixX3d& P, double t);

//! d^r/dt^r of the Bernstein basis of degree k at t (#k+1), from the textbook formula
//! (independent of coons' derivative nets).
Eigen::VectorXd bernstein_basis_derivative(int k, int r, double t);

//! The registry entry of a backend built into every coons binary (eigen-ldlt, eigen-lu, ...) or of
//! an optional one the caller has checked for; throws std::invalid_argument for an unknown name.
const solvers::SolverInfo& backend(const std::string& name);

//! The objective parse_objective reads from `name`; throws std::invalid_argument for a name it refuses.
Objective objective_named(const std::string& name);

//! A fresh folder under the system's temporary directory, removed with everything in it.
struct TempDir {
  std::filesystem::path path;
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path / name).string(); }
  //! Writes `text` to the file `name` in the folder and returns its path.
  std::string write(const std::string& name, const std::string& text) const;
};

//! Whether `text` holds `part`.
bool contains(const std::string& text, const std::string& part);
//! The lines, each ended by "\n".
std::string joined_lines(const std::vector<std::string>& lines);

//! Run a shell command; returns the exit status and fills stdout/stderr.
struct CommandResult {
  int status = -1;
  std::string out, err;
};
CommandResult run_command(const std::string& command);

}  // namespace coons::test
