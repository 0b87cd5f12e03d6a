#include "obj_export.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <Eigen/Geometry>
#include <cmath>

#include "coons/net/bernstein.h"

namespace coons {

namespace {
void write_vertex(std::ostream& out, const char* tag, const Eigen::RowVector3d& p) {
  fmt::print(out, "{} {} {} {}\n", tag, p(0), p(1), p(2));
}

}  // namespace

void write_surface_obj(std::ostream& out, const ControlNet& net, int k) {
  const Eigen::MatrixX3d P = sample_surface(net, k, k);
  const ControlNet du = derivative_net(net, 1, 0), dv = derivative_net(net, 0, 1);
  fmt::print(out, "# coons: Bezier surface of degree ({}, {}) sampled {}x{}\n", net.m, net.n, k, k);
  for (Eigen::Index r = 0; r < P.rows(); ++r) write_vertex(out, "v", P.row(r));
  // the direction only: each tangent scaled first (bit for bit the same where nothing underflows;
  // products of tangents of size 1e-90 would underflow)
  const auto normal_at = [&](double u, double v) -> Eigen::Vector3d {
    return unit_scaled(evaluate(du, u, v)).transpose().cross(unit_scaled(evaluate(dv, u, v)).transpose());
  };
  for (int s = 0; s < k; ++s)
    for (int t = 0; t < k; ++t) {
      const double u = double(s) / (k - 1), v = double(t) / (k - 1);
      Eigen::Vector3d normal = normal_at(u, v);
      // Where a side collapses to a point (a tangent vanishes) or the tangents are parallel, the
      // normal is the limit from inside: taken a little towards the centre of the parameter square.
      // (It was a placeholder (0, 0, 1), whatever the surface did there.)
      for (double step = 1e-7; !(normal.norm() > 1e-12) && step < 0.1; step *= 100)
        normal = normal_at(u + (0.5 - u) * step, v + (0.5 - v) * step);
      const double len = normal.norm();
      normal = len > 0 ? Eigen::Vector3d(normal / len) : Eigen::Vector3d(0, 0, 1);
      write_vertex(out, "vn", normal.transpose());
    }
  auto id = [k](int s, int t) { return s * k + t + 1; };
  for (int s = 0; s + 1 < k; ++s)
    for (int t = 0; t + 1 < k; ++t) {
      const int a = id(s, t), b = id(s + 1, t), c = id(s + 1, t + 1), d = id(s, t + 1);
      fmt::print(out, "f {0}//{0} {1}//{1} {2}//{2}\nf {0}//{0} {2}//{2} {3}//{3}\n", a, b, c, d);
    }
}

void write_net_obj(std::ostream& out, const ControlNet& net) {
  fmt::print(out, "# coons: control net of degree ({}, {})\n", net.m, net.n);
  for (Eigen::Index r = 0; r < net.points.rows(); ++r) write_vertex(out, "v", net.points.row(r));
  for (int i = 0; i < net.m; ++i)
    for (int j = 0; j < net.n; ++j)
      fmt::print(out, "f {} {} {} {}\n", net.index(i, j) + 1, net.index(i + 1, j) + 1, net.index(i + 1, j + 1) + 1,
                 net.index(i, j + 1) + 1);
}

}  // namespace coons
