#include "mesh_export.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cmath>
#include <utility>
#include <vector>

namespace coons {

namespace {

// The scalar fields of a sample set, in a fixed order; "singular" is 1 where the normal (and so
// the curvatures) is undefined, 0 elsewhere.
struct Fields {
  Eigen::VectorXd singular;
  std::vector<std::pair<const char*, const Eigen::VectorXd*>> list;
  explicit Fields(const SurfaceSamples& s) : singular(s.normals.rows()) {
    for (Eigen::Index r = 0; r < singular.size(); ++r) singular(r) = s.normals.row(r).allFinite() ? 0.0 : 1.0;
    list = {{"mean_curvature", &s.mean_curvature}, {"gaussian_curvature", &s.gaussian_curvature}, {"twist", &s.twist}};
    if (s.distance) list.emplace_back("distance", &*s.distance);
    if (s.parametric_distance) list.emplace_back("parametric_distance", &*s.parametric_distance);
    list.emplace_back("singular", &singular);
  }
};

}  // namespace

double finite_or_zero(double x) { return std::isfinite(x) ? x : 0.0; }

void write_vtk_scalars(std::ostream& out, const char* name, const Eigen::VectorXd& values) {
  out << "        <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
  for (Eigen::Index r = 0; r < values.size(); ++r)
    out << (r % 8 ? " " : "          ") << fmt::format("{}", finite_or_zero(values(r))) << (r % 8 == 7 ? "\n" : "");
  out << (values.size() % 8 ? "\n" : "") << "        </DataArray>\n";
}

void write_vtk_vectors(std::ostream& out, const char* name, const Eigen::MatrixX3d& v) {
  out << "        <DataArray type=\"Float64\"" << (name[0] ? fmt::format(" Name=\"{}\"", name) : std::string())
      << " NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (Eigen::Index r = 0; r < v.rows(); ++r)
    fmt::print(out, "          {} {} {}\n", finite_or_zero(v(r, 0)), finite_or_zero(v(r, 1)), finite_or_zero(v(r, 2)));
  out << "        </DataArray>\n";
}

void write_grid_obj(std::ostream& out, const SurfaceSamples& s, const std::string& comment) {
  const int k = s.k;
  fmt::print(out, "# coons: surface sampled {}x{}{}\n", k, k, comment.empty() ? "" : " — " + comment);
  for (Eigen::Index r = 0; r < s.points.rows(); ++r)
    fmt::print(out, "v {} {} {}\n", s.points(r, 0), s.points(r, 1), s.points(r, 2));
  // A sample without a normal (a side collapsed to a point, parallel tangents) gets that of the
  // first sample with one on the way to the centre of the grid: the limit from inside, to the
  // grid's resolution (it was a placeholder (0, 0, 1)). (0, 0, 1) only when no sample has one.
  const auto normal_of = [&](int a, int b) -> Eigen::RowVector3d {
    for (int step = 0; step < k; ++step) {
      const int a2 = a + (a < k / 2 ? step : -step), b2 = b + (b < k / 2 ? step : -step);
      if (a2 < 0 || a2 >= k || b2 < 0 || b2 >= k) break;
      if (s.normals.row(a2 * k + b2).allFinite()) return s.normals.row(a2 * k + b2);
    }
    return Eigen::RowVector3d(0, 0, 1);
  };
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const Eigen::RowVector3d n = normal_of(a, b);
      fmt::print(out, "vn {} {} {}\n", n(0), n(1), n(2));
    }
  auto id = [k](int a, int b) { return a * k + b + 1; };
  for (int a = 0; a + 1 < k; ++a)
    for (int b = 0; b + 1 < k; ++b) {
      const int p = id(a, b), q = id(a + 1, b), r = id(a + 1, b + 1), t = id(a, b + 1);
      fmt::print(out, "f {0}//{0} {1}//{1} {2}//{2}\nf {0}//{0} {2}//{2} {3}//{3}\n", p, q, r, t);
    }
}

void write_grid_ply(std::ostream& out, const SurfaceSamples& s, const std::string& comment) {
  const int k = s.k;
  const Fields field_set(s);
  const auto& fields = field_set.list;
  out << "ply\nformat ascii 1.0\ncomment coons: surface sampled on a " << k << "x" << k << " grid\n";
  if (!comment.empty()) out << "comment " << comment << '\n';
  out << "element vertex " << k * k << "\nproperty double x\nproperty double y\nproperty double z\n"
      << "property double nx\nproperty double ny\nproperty double nz\n";
  for (const auto& [name, values] : fields) out << "property double " << name << '\n';
  out << "element face " << (k - 1) * (k - 1) << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int r = 0; r < k * k; ++r) {
    fmt::print(out, "{} {} {}", s.points(r, 0), s.points(r, 1), s.points(r, 2));
    for (int c = 0; c < 3; ++c) fmt::print(out, " {}", finite_or_zero(s.normals(r, c)));
    for (const auto& [name, values] : fields) fmt::print(out, " {}", finite_or_zero((*values)(r)));
    out << '\n';
  }
  for (int a = 0; a + 1 < k; ++a)
    for (int b = 0; b + 1 < k; ++b)
      fmt::print(out, "4 {} {} {} {}\n", a * k + b, (a + 1) * k + b, (a + 1) * k + b + 1, a * k + b + 1);
}

void write_grid_vts(std::ostream& out, const SurfaceSamples& s) {
  const int k = s.k;
  // VTK's structured grids run x (i) fastest: point index i + k·j with i ↔ v-index b, j ↔ u-index a,
  // which is exactly our row a·k + b.
  const std::string extent = fmt::format("0 {} 0 {} 0 0", k - 1, k - 1);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"StructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <StructuredGrid WholeExtent=\"" << extent << "\">\n"
      << "    <Piece Extent=\"" << extent << "\">\n"
      << "      <PointData Scalars=\"mean_curvature\" Normals=\"Normals\">\n";
  const Fields fields(s);
  for (const auto& [name, values] : fields.list) write_vtk_scalars(out, name, *values);
  write_vtk_vectors(out, "Normals", s.normals);
  out << "      </PointData>\n      <Points>\n";
  write_vtk_vectors(out, "", s.points);
  out << "      </Points>\n    </Piece>\n  </StructuredGrid>\n</VTKFile>\n";
}

}  // namespace coons
