#include "pole_scan.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace coons {

namespace {

constexpr int kBisections = 60;
constexpr int kGoldenSteps = 80;

// The singularity at s when f(s) is not finite or beyond `limit` in magnitude.
std::optional<Singularity> singular_at(int component, double s, double value, double limit) {
  if (std::isfinite(value) && std::abs(value) <= limit) return std::nullopt;
  return Singularity{component, s, value};
}

}  // namespace

std::optional<Singularity> find_singularity(const AnalyticCurve& c, int samples, double growth) {
  const int n = std::max(samples, 2);
  const auto count = static_cast<std::size_t>(n);
  std::vector<double> s(count, 0.0);
  std::vector<Eigen::RowVector3d> p(count, Eigen::RowVector3d::Zero());
  for (int k = 0; k < n; ++k) {
    s[std::size_t(k)] = double(k) / (n - 1);
    p[std::size_t(k)] = c.at(s[std::size_t(k)]);
  }
  // The limit is relative to the whole curve's size: a coordinate whose samples are rounding
  // noise (0.01 sin(1024 pi t) at t = k/1024) must not make its own values of 0.01 a pole. A sample
  // counts towards the size at most as much as its larger neighbour (an end sample as its one
  // neighbour): a pole on a sample itself (tan(pi t) at t = 1/2, or tan(t) at the end of [0, pi/2],
  // is 1.6e16, finite) would otherwise be the size and never exceed it. A bump narrower than the
  // samples' spacing and 1e8 times taller than its neighbours looks the same and is taken for a pole.
  double size = 0;
  for (int k = 0; k < n; ++k)
    for (int comp = 0; comp < 3; ++comp) {
      const auto magnitude = [&](int i) {
        const double x = p[std::size_t(i)](comp);
        return std::isfinite(x) ? std::abs(x) : 0.0;
      };
      const double neighbour = std::max(k > 0 ? magnitude(k - 1) : 0.0, k + 1 < n ? magnitude(k + 1) : 0.0);
      size = std::max(size, std::min(magnitude(k), neighbour));
    }
  for (int comp = 0; comp < 3; ++comp) {
    const auto f = [&](double x) { return c.at(x)(comp); };
    const auto v = [&](int k) { return p[std::size_t(k)](comp); };
    double largest = 0;
    for (int k = 0; k < n; ++k) {
      if (const auto bad = singular_at(comp, s[std::size_t(k)], v(k), HUGE_VAL)) return bad;
      largest = std::max(largest, std::abs(v(k)));
    }
    if (largest == 0) continue;  // zero at every sample: nothing to climb
    const double limit = growth * size, notable = 0.1 * largest;
    for (int k = 0; k < n; ++k)
      if (const auto bad = singular_at(comp, s[std::size_t(k)], v(k), limit)) return bad;
    for (int k = 0; k + 1 < n; ++k) {
      // a change of sign next to large values: a root or a pole of odd order in between
      if (v(k) * v(k + 1) < 0 && std::max(std::abs(v(k)), std::abs(v(k + 1))) >= notable) {
        double a = s[std::size_t(k)], b = s[std::size_t(k) + 1], fa = v(k);
        for (int it = 0; it < kBisections && b - a > 0; ++it) {
          const double m = 0.5 * (a + b), fm = f(m);
          if (const auto bad = singular_at(comp, m, fm, limit)) return bad;
          if ((fm < 0) == (fa < 0)) {
            a = m;
            fa = fm;
          } else {
            b = m;
          }
        }
      }
    }
    for (int k = 0; k < n; ++k) {
      // a peak of the magnitude: a pole of even order (or a bump) in [s_{k-1}, s_{k+1}], the
      // end samples included (a pole at t = 0.0003 peaks at the first sample)
      const int before = std::max(k - 1, 0), after = std::min(k + 1, n - 1);
      if (std::abs(v(k)) >= notable && std::abs(v(k)) >= std::abs(v(before)) && std::abs(v(k)) >= std::abs(v(after))) {
        const double ratio = 0.5 * (std::sqrt(5.0) - 1);
        double a = s[std::size_t(before)], b = s[std::size_t(after)];
        double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
        double f1 = std::abs(f(x1)), f2 = std::abs(f(x2));
        for (int it = 0; it < kGoldenSteps; ++it) {
          if (const auto bad = singular_at(comp, x1, f1, limit)) return bad;
          if (const auto bad = singular_at(comp, x2, f2, limit)) return bad;
          if (f1 >= f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - ratio * (b - a);
            f1 = std::abs(f(x1));
          } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + ratio * (b - a);
            f2 = std::abs(f(x2));
          }
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace coons
