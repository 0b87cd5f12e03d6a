// One value type for every surface of the Coons family: its type (the `type` of docs/formats.md's
// surface descriptions), its data, and the Boolean sum it evaluates through. Evaluation gives the
// point and the partial derivatives up to order 2; bezier_net() the exact net when the surface is
// polynomial; fitted_net() an approximating net (every non-Bézier curve replaced by its Bézier
// fit) with the fits' deviations, so that analytic examples can be compared with discrete nets.
// Based on: LN0–LN4 (the family), summarised in docs/math.md §6.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "coons/net/control_net.h"
#include "coons/surfaces/boolean_sum.h"
#include "coons/surfaces/conoid.h"
#include "coons/surfaces/general_coons.h"
#include "coons/surfaces/hermite_patch.h"
#include "coons/surfaces/ruled_surface.h"

namespace coons {

enum class SurfaceType {
  kRuled,
  kSectorial,
  kBilinear,
  kConoid,
  kBilinearCoons,
  kHermiteCoons,
  kFerguson,
  kHermite16,
  kGeneralCoons,
  kBezier,  //!< a tensor-product Bézier net (e.g. a discrete Coons or α-net)
};

//! "ruled", "sectorial", "bilinear", "conoid", "bilinear-coons", "hermite-coons", "ferguson",
//! "hermite16", "general-coons", "bezier".
const char* to_string(SurfaceType t);
std::optional<SurfaceType> surface_type_from_string(const std::string& name);
std::vector<std::string> surface_type_names();

//! Ruled and sectorial: RuledSurface; the two Coons blends: BoundaryCurves; Ferguson and 16-vector:
//! HermitePatch; Bézier: ControlNet.
using SurfaceData =
    std::variant<RuledSurface, BilinearSurface, Conoid, BoundaryCurves, HermitePatch, GeneralCoonsData, ControlNet>;

class Surface {
 public:
  //! Precondition: the data alternative matches the type (see SurfaceData).
  Surface(SurfaceType type, SurfaceData data);

  [[nodiscard]] SurfaceType type() const { return type_; }
  [[nodiscard]] const SurfaceData& data() const { return data_; }

  //! r and its partial derivatives up to order 2 at (u, v) ∈ [0, 1]².
  [[nodiscard]] SurfacePoint evaluate(double u, double v) const;
  [[nodiscard]] Eigen::RowVector3d at(double u, double v) const { return evaluate(u, v).p; }

  //! The exact Bézier net when every curve is a Bézier curve (always for bilinear, Ferguson,
  //! 16-vector and Bézier surfaces); nullopt otherwise.
  [[nodiscard]] std::optional<ControlNet> bezier_net() const;

  //! The curves the surface is built from, by their description field ("bottom", "curves[0]",
  //! "directrix", "du_left", …).
  [[nodiscard]] std::vector<std::pair<std::string, const Curve*>> curves() const;

  //! The same construction with each curve replaced by f(field, curve).
  [[nodiscard]] Surface map_curves(const std::function<Curve(const std::string&, const Curve&)>& f) const;

 private:
  SurfaceType type_;
  SurfaceData data_;
  BooleanSum sum_;  // unused for kBezier
};

// Constructors by family (no validation: see surface_io.h for checked input).
Surface make_ruled(Curve c0, Curve c1);
Surface make_sectorial(Curve c, const Eigen::RowVector3d& apex);
Surface make_bilinear(const std::array<Eigen::RowVector3d, 4>& corners);
Surface make_conoid(Conoid c);
Surface make_coons(BoundaryCurves b, CoonsBlending blending);
Surface make_ferguson(const std::array<Eigen::RowVector3d, 4>& corners, const std::array<Eigen::RowVector3d, 4>& du,
                      const std::array<Eigen::RowVector3d, 4>& dv);
Surface make_hermite16(HermitePatch h);
Surface make_general_coons(GeneralCoonsData g);
Surface make_bezier_surface(ControlNet net);

struct CurveFitReport {
  std::string curve;         //!< field name
  int degree = 0;            //!< of the fit used
  int fitted_degree = 0;     //!< of its least-squares fit before the exact elevation (≤ degree)
  double max_deviation = 0;  //!< of the Bézier fit
  bool on_surface = true;    //!< a side of the surface; false for a cross-derivative (du_*, dv_*)
};

struct FittedNet {
  ControlNet net;
  bool exact = true;  //!< every curve was already Bézier: net is bezier_net()
  int fit_degree = 0;
  std::vector<CurveFitReport> fits;  //!< one per non-Bézier curve
  double max_curve_deviation = 0;
};

//! bezier_net() when it exists; else the net of the same construction over Bézier fits
//! (fit_bezier: end points interpolated) of every non-Bézier curve: at the lowest degree ≤
//! `fit_degree` that reproduces the curve to rounding (1e-13 of its size — a polynomial written as
//! an expression gets its own degree), else at `fit_degree` ≥ 1.
FittedNet fitted_net(const Surface& s, int fit_degree);

}  // namespace coons
