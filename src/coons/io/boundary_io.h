// Reading the boundary JSON of docs/formats.md: four sides (bottom/top: m+1 points, left/right: n+1),
// optionally with the second ring as "ribbons", or a full "net" (m+1 rows of n+1 points), optionally
// with "rings" (how many outer rings are data) and a "free" grid (the points to solve for). Every
// violation throws InputError naming the file, the field (with the index) and the reason.
//
//   ribbons  {"bottom": b[i][1], "top": b[i][n−1] (i = 0..m), "left": b[1][j], "right": b[m−1][j]
//            (j = 0..n)}: all four or none; their ends are points of the sides and of each other
//            and must agree to the corner tolerance. Needs m, n ≥ 4 (two data rings around at
//            least one free point); a smaller net with two data rings is written in the "net" form.
//   rings    an integer from 1 to min(m, n)/2 + 1 (the rings the net has; all of them: nothing is free).
//   free     (m+1) rows of (n+1) values 0/1; a free point must lie inside the data rings.
//   knots_u, knots_v, degree_spline   the sides are B-spline curves (bspline_boundary_io.h); sides
//            form without ribbons only. The file's `bspline` then holds them, made compatible.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/io/bspline_boundary_io.h"
#include "coons/io/misspelt_fields.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"

namespace coons {

struct BoundaryReadOptions {
  //! Corners must agree to this fraction of the bounding-box diagonal (docs/formats.md: 1e-9).
  double corner_tolerance = 1e-9;
  //! 0: a model of any size. The searches ask for kMinModelSize (json_file.h): a model whose largest
  //! coordinate magnitude is below it (and not zero) is then an InputError at that point.
  double min_model_size = 0;
};

//! The point of largest coordinate magnitude of a model (BoundaryReadOptions::min_model_size).
struct LargestPoint {
  double magnitude = 0;
  std::string field;  //!< where it is: "name[k]"
  //! The points of `list` (#points by 3), row k named "name[k]".
  void add(const std::string& name, const Eigen::Ref<const Eigen::MatrixX3d>& list);
  //! An InputError at `field` when 0 < magnitude < min_size (require_model_size, json_file.h).
  void require(double min_size, const std::string& source) const;
};

//! The second ring of a net given with its sides: bottom = b[i][1], top = b[i][n−1] (#m+1 by 3),
//! left = b[1][j], right = b[m−1][j] (#n+1 by 3).
struct Ribbons {
  Eigen::MatrixX3d bottom, top, left, right;
};

struct BoundaryFile {
  Boundary boundary;               //!< always present (from the sides or the net's frame)
  std::optional<ControlNet> net;   //!< present when the file held "net"
  std::optional<Ribbons> ribbons;  //!< present when the sides came with "ribbons"
  int rings = 1;                   //!< data rings: "rings" of the net form, 2 with ribbons, else 1
  FreeGrid free;                   //!< the "free" grid of the net form (empty: inside the rings)
  //! present when the sides came with knots_u, knots_v and degree_spline (a B-spline boundary)
  std::optional<BSplineInput> bspline;
  //! fields one edit from one coons reads ("fre" for "free"): ignored, for the commands to warn about
  std::vector<MisspeltField> misspelt;
};

//! The top-level fields of a rectangular boundary file (docs/formats.md), those people write for
//! people (description, source) included.
const std::vector<std::string>& boundary_file_fields();

//! Parse and validate. `source` names the input in error messages (a path or "<stdin>").
BoundaryFile parse_boundary(const nlohmann::json& doc, const std::string& source,
                            const BoundaryReadOptions& options = {});

//! Read a file and parse it; unreadable files and malformed JSON are InputErrors too.
BoundaryFile read_boundary_file(const std::string& path, const BoundaryReadOptions& options = {});

//! The mask problem a file describes: the net form gives its net, rings and free grid; sides with
//! ribbons a net holding both data rings (rings = 2) with the discrete Coons net of the inner ring
//! inside as start values; sides alone the discrete Coons net with rings = 1. Never throws (the
//! file was validated when parsed); whether a mask fits the problem is check_stencil_problem's.
StencilProblem stencil_problem(const BoundaryFile& file);

//! True for the classical problem: one data ring and no free grid.
bool is_classical(const BoundaryFile& file);

}  // namespace coons
