#include "coons/tri/tri_sampling.h"

#include <catch2/catch.hpp>
#include <set>

#include "tri/tri_fixtures.h"

using namespace coons::tri;
using namespace coons::tri_test;

TEST_CASE("tri_grid_triangles: (K-1)^2 counter-clockwise triangles covering the triangle once", "[tri]") {
  for (int k = 2; k <= 12; ++k) {
    const auto triangles = tri_grid_triangles(k);
    REQUIRE(triangles.size() == size_t((k - 1) * (k - 1)));
    double area = 0;
    std::set<int> used;
    for (const auto& t : triangles) {
      Eigen::Vector2d p[3];
      for (int c = 0; c < 3; ++c) {
        used.insert(t[c]);
        // find (r, s) of the vertex: row order
        int r = 0;
        while (net_index(k - 1, 0, r + 1) <= t[c] && r + 1 < k) ++r;
        const int s = t[c] - int(net_index(k - 1, 0, r));
        const Eigen::Vector3d uvw = tri_sample_uvw(k, r, s);
        p[c] = {uvw(0), uvw(1)};
      }
      const double signed_area = 0.5 * ((p[1] - p[0])(0) * (p[2] - p[0])(1) - (p[1] - p[0])(1) * (p[2] - p[0])(0));
      REQUIRE(signed_area > 0);
      area += signed_area;
    }
    REQUIRE(area == Approx(0.5).epsilon(1e-12));
    REQUIRE(used.size() == size_t(net_size(k - 1)));
  }
}

TEST_CASE("sample_tri_surface: points on the surface, normal and curvatures of a paraboloid", "[tri]") {
  // (x, y, (x² + y²)/2) with x = u, y = v: b_ijk = (i/2, j/2, z), z = 1/2 at (2,0,0) and (0,2,0), else 0.
  TriNet net(2);
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j + k <= 2; ++j) {
      const int i = 2 - j - k;
      net.at(i, j, k) << i / 2.0, j / 2.0, (i == 2 || j == 2) ? 0.5 : 0.0;
    }
  const TriSurfaceSamples s = sample_tri_surface(net, 9);
  REQUIRE(s.points.rows() == net_size(8));
  for (int r = 0; r < 9; ++r)
    for (int q = 0; q + r < 9; ++q) {
      const Eigen::Index row = net_index(8, q, r);
      const double x = (8 - r - q) / 8.0, y = q / 8.0;
      REQUIRE((s.points.row(row) - Eigen::RowVector3d(x, y, (x * x + y * y) / 2)).norm() < 1e-14);
      const Eigen::RowVector3d normal = Eigen::RowVector3d(-x, -y, 1).normalized();
      REQUIRE((s.normals.row(row) - normal).norm() < 1e-13);
      REQUIRE(s.singular(row) == 0);
    }
  const Eigen::Index origin = net_index(8, 0, 8);  // (u, v, w) = (0, 0, 1)
  REQUIRE(s.mean_curvature(origin) == Approx(1.0).epsilon(1e-12));
  REQUIRE(s.gaussian_curvature(origin) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("sample_tri_surface: a collapsed corner is marked singular, with zero normal", "[tri]") {
  TriNet net = random_tri_net(3, 4);
  // sides through b300 collapse: the neighbours of the corner coincide with it
  net.at(2, 1, 0) = net.at(3, 0, 0);
  net.at(2, 0, 1) = net.at(3, 0, 0);
  const TriSurfaceSamples s = sample_tri_surface(net, 5);
  const Eigen::Index corner = net_index(4, 0, 0);
  REQUIRE(s.singular(corner) == 1);
  REQUIRE(s.normals.row(corner).isZero());
  REQUIRE(s.singular.sum() == 1);
}

TEST_CASE("sample_tri_surface: normals and curvatures of a model of any size, scaled as they should", "[tri]") {
  // at a model size of 1e-100 the cross product of the derivatives underflowed: every normal came
  // out 0 (singular) or (0, 0, 1) and every curvature 0
  const TriNet net = random_tri_net(4, 9);
  const TriSurfaceSamples one = sample_tri_surface(net, 7);
  for (const double scale : {1e-100, 1e-150, 1e100}) {
    INFO("scale " << scale);
    TriNet small = net;
    small.points *= scale;
    const TriSurfaceSamples s = sample_tri_surface(small, 7);
    CHECK(s.singular == one.singular);
    CHECK((s.normals - one.normals).cwiseAbs().maxCoeff() < 1e-13);
    for (Eigen::Index row = 0; row < s.points.rows(); ++row) {
      if (one.singular(row)) continue;
      CHECK(s.mean_curvature(row) * scale == Approx(one.mean_curvature(row)).epsilon(1e-11).margin(1e-300));
      CHECK(s.gaussian_curvature(row) * scale * scale ==
            Approx(one.gaussian_curvature(row)).epsilon(1e-11).margin(1e-300));
    }
  }
}
