#include "tri_mesh_export.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "mesh_export.h"

namespace coons {

namespace {

std::vector<std::pair<const char*, Eigen::VectorXd>> scalar_fields(const tri::TriSurfaceSamples& s) {
  return {{"mean_curvature", s.mean_curvature},
          {"gaussian_curvature", s.gaussian_curvature},
          {"singular", s.singular.cast<double>()}};
}

}  // namespace

void write_tri_surface_obj(std::ostream& out, const tri::TriSurfaceSamples& s, int degree) {
  fmt::print(out, "# coons: triangular Bezier surface of degree {} sampled with {} points per side\n", degree, s.k);
  for (Eigen::Index r = 0; r < s.points.rows(); ++r)
    fmt::print(out, "v {} {} {}\n", s.points(r, 0), s.points(r, 1), s.points(r, 2));
  for (Eigen::Index r = 0; r < s.normals.rows(); ++r) {
    if (s.singular(r)) {
      out << "vn 0 0 1\n";
    } else {
      fmt::print(out, "vn {} {} {}\n", s.normals(r, 0), s.normals(r, 1), s.normals(r, 2));
    }
  }
  for (const auto& t : s.triangles) fmt::print(out, "f {0}//{0} {1}//{1} {2}//{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
}

void write_tri_net_obj(std::ostream& out, const tri::TriNet& net) {
  fmt::print(out, "# coons: triangular control net of degree {} (vertices in the row order of docs/formats.md)\n",
             net.n);
  for (Eigen::Index r = 0; r < net.points.rows(); ++r)
    fmt::print(out, "v {} {} {}\n", net.points(r, 0), net.points(r, 1), net.points(r, 2));
  if (net.n == 0) return;
  for (const auto& t : tri::tri_grid_triangles(net.n + 1))
    fmt::print(out, "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
}

void write_tri_surface_ply(std::ostream& out, const tri::TriSurfaceSamples& s, int degree) {
  const auto fields = scalar_fields(s);
  out << "ply\nformat ascii 1.0\ncomment coons: triangular Bezier surface of degree " << degree << " sampled with "
      << s.k << " points per side\n"
      << "element vertex " << s.points.rows() << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "property double nx\nproperty double ny\nproperty double nz\n";
  for (const auto& field : fields) out << "property double " << field.first << '\n';
  out << "element face " << s.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index r = 0; r < s.points.rows(); ++r) {
    fmt::print(out, "{} {} {}", s.points(r, 0), s.points(r, 1), s.points(r, 2));
    for (int c = 0; c < 3; ++c) fmt::print(out, " {}", finite_or_zero(s.normals(r, c)));
    for (const auto& field : fields) fmt::print(out, " {}", finite_or_zero(field.second(r)));
    out << '\n';
  }
  for (const auto& t : s.triangles) fmt::print(out, "3 {} {} {}\n", t[0], t[1], t[2]);
}

void write_tri_surface_vtu(std::ostream& out, const tri::TriSurfaceSamples& s) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << s.points.rows() << "\" NumberOfCells=\"" << s.triangles.size() << "\">\n"
      << "      <PointData Scalars=\"mean_curvature\" Normals=\"Normals\">\n";
  for (const auto& field : scalar_fields(s)) write_vtk_scalars(out, field.first, field.second);
  write_vtk_vectors(out, "Normals", s.normals);
  out << "      </PointData>\n      <Points>\n";
  write_vtk_vectors(out, "", s.points);
  out << "      </Points>\n      <Cells>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : s.triangles) fmt::print(out, "          {} {} {}\n", t[0], t[1], t[2]);
  out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t c = 0; c < s.triangles.size(); ++c)
    out << (c % 8 ? " " : "          ") << 3 * (c + 1) << (c % 8 == 7 ? "\n" : "");
  out << (s.triangles.size() % 8 ? "\n" : "") << "        </DataArray>\n"
      << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t c = 0; c < s.triangles.size(); ++c) out << (c % 8 ? " " : "          ") << 5 << (c % 8 == 7 ? "\n" : "");
  out << (s.triangles.size() % 8 ? "\n" : "") << "        </DataArray>\n      </Cells>\n    </Piece>\n"
      << "  </UnstructuredGrid>\n</VTKFile>\n";
}

}  // namespace coons
