#include "coons/curves/random_boundary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "coons/net/degree_elevation.h"

namespace coons {

bool RandomSmoothOptions::is_valid(std::string* why) const {
  std::string reason;
  if (side_degree < 1 || side_degree > 20)
    reason = fmt::format("the side degree must be in [1, 20], not {}", side_degree);
  else if (!(std::isfinite(height) && height >= 0))
    reason = "the height must be finite and not negative";
  else if (!(std::isfinite(wiggle) && wiggle >= 0 && wiggle < 0.5))
    reason = "the wiggle must be in [0, 0.5)";
  if (why && !reason.empty()) *why = reason;
  return reason.empty();
}

Boundary random_smooth_boundary(std::uint64_t seed, int index, const RandomSmoothOptions& options) {
  std::seed_seq sequence{std::uint32_t(seed & 0xffffffffU), std::uint32_t(seed >> 32), std::uint32_t(index)};
  std::mt19937_64 g(sequence);
  auto uniform = [&](double amplitude) {  // uniform in [−amplitude, amplitude)
    const double u = double(g() >> 11) * 0x1.0p-53;
    return amplitude * (2 * u - 1);
  };
  const int p = options.side_degree;
  // corners: bottom-left, bottom-right, top-right, top-left
  Eigen::RowVector3d corner[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (auto& c : corner) c.z() = uniform(options.height);
  auto side = [&](const Eigen::RowVector3d& from, const Eigen::RowVector3d& to) {
    Eigen::MatrixX3d s(p + 1, 3);
    for (int i = 0; i <= p; ++i) {
      const double t = double(i) / p;
      s.row(i) = (1 - t) * from + t * to;
      if (i > 0 && i < p) {
        s(i, 0) += uniform(options.wiggle);
        s(i, 1) += uniform(options.wiggle);
        s(i, 2) += uniform(options.height);
      }
    }
    return s;
  };
  Boundary b;
  b.name = fmt::format("random-smooth-{}-{}", seed, index);
  b.m = b.n = p;
  b.bottom = side(corner[0], corner[1]);  // b[i][0]
  b.top = side(corner[3], corner[2]);     // b[i][n]
  b.left = side(corner[0], corner[3]);    // b[0][j]
  b.right = side(corner[1], corner[2]);   // b[m][j]
  return b;
}

Boundary random_smooth_displacement(std::uint64_t seed, int index, const RandomSmoothOptions& options) {
  RandomSmoothOptions flat = options;
  flat.height = 0;
  flat.wiggle = 0;
  Boundary d = random_smooth_boundary(seed, index, options);
  const Boundary square = random_smooth_boundary(seed, index, flat);  // the same draws, all scaled by 0
  d.bottom -= square.bottom;
  d.top -= square.top;
  d.left -= square.left;
  d.right -= square.right;
  return d;
}

Boundary perturbed_boundary(const Boundary& base, double amplitude, std::uint64_t seed, int index,
                            const RandomSmoothOptions& options) {
  const int m = std::max(base.m, options.side_degree), n = std::max(base.n, options.side_degree);
  const double scale = amplitude * bounding_box_diagonal(base);
  Boundary b = elevate_boundary(base, m, n);
  const Boundary d = elevate_boundary(random_smooth_displacement(seed, index, options), m, n);
  b.bottom += scale * d.bottom;
  b.top += scale * d.top;
  b.left += scale * d.left;
  b.right += scale * d.right;
  b.name = fmt::format("{}-perturbed-{}-{}", base.name, seed, index);
  return b;
}

std::vector<Boundary> random_smooth_family(std::uint64_t seed, int count, const RandomSmoothOptions& options,
                                           int first) {
  std::vector<Boundary> family;
  family.reserve(std::max(count, 0));
  for (int k = 0; k < count; ++k) family.push_back(random_smooth_boundary(seed, first + k, options));
  return family;
}

}  // namespace coons
