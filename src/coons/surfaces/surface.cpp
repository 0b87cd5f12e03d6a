#include "surface.h"

#include <algorithm>
#include <cassert>

#include "coons/curves/bezier_fit.h"
#include "coons/net/bernstein.h"

namespace coons {

namespace {

struct Named {
  SurfaceType type;
  const char* name;
};
constexpr Named kNames[] = {
    {SurfaceType::kRuled, "ruled"},
    {SurfaceType::kSectorial, "sectorial"},
    {SurfaceType::kBilinear, "bilinear"},
    {SurfaceType::kConoid, "conoid"},
    {SurfaceType::kBilinearCoons, "bilinear-coons"},
    {SurfaceType::kHermiteCoons, "hermite-coons"},
    {SurfaceType::kFerguson, "ferguson"},
    {SurfaceType::kHermite16, "hermite16"},
    {SurfaceType::kGeneralCoons, "general-coons"},
    {SurfaceType::kBezier, "bezier"},
};

BooleanSum make_sum(SurfaceType type, const SurfaceData& data) {
  switch (type) {
    case SurfaceType::kRuled:
    case SurfaceType::kSectorial:
      return to_boolean_sum(std::get<RuledSurface>(data));
    case SurfaceType::kBilinear:
      return to_boolean_sum(std::get<BilinearSurface>(data));
    case SurfaceType::kConoid:
      return to_boolean_sum(std::get<Conoid>(data));
    case SurfaceType::kBilinearCoons:
      return to_boolean_sum(std::get<BoundaryCurves>(data), CoonsBlending::kLinear);
    case SurfaceType::kHermiteCoons:
      return to_boolean_sum(std::get<BoundaryCurves>(data), CoonsBlending::kHermite);
    case SurfaceType::kFerguson:
    case SurfaceType::kHermite16:
      return to_boolean_sum(std::get<HermitePatch>(data));
    case SurfaceType::kGeneralCoons:
      return to_boolean_sum(std::get<GeneralCoonsData>(data));
    case SurfaceType::kBezier:
      (void)std::get<ControlNet>(data);
      return {};
  }
  return {};
}

}  // namespace

const char* to_string(SurfaceType t) {
  for (const auto& n : kNames)
    if (n.type == t) return n.name;
  return "?";
}

std::optional<SurfaceType> surface_type_from_string(const std::string& name) {
  for (const auto& n : kNames)
    if (name == n.name) return n.type;
  return std::nullopt;
}

std::vector<std::string> surface_type_names() {
  std::vector<std::string> out;
  for (const auto& n : kNames) out.emplace_back(n.name);
  return out;
}

Surface::Surface(SurfaceType type, SurfaceData data)
    : type_(type), data_(std::move(data)), sum_(make_sum(type_, data_)) {}

SurfacePoint Surface::evaluate(double u, double v) const {
  if (type_ != SurfaceType::kBezier) return coons::evaluate(sum_, u, v);
  const ControlNet& net = std::get<ControlNet>(data_);
  SurfacePoint s;
  s.p = coons::evaluate(net, u, v);
  s.du = evaluate_derivative(net, 1, 0, u, v);
  s.dv = evaluate_derivative(net, 0, 1, u, v);
  s.duu = evaluate_derivative(net, 2, 0, u, v);
  s.duv = evaluate_derivative(net, 1, 1, u, v);
  s.dvv = evaluate_derivative(net, 0, 2, u, v);
  return s;
}

std::optional<ControlNet> Surface::bezier_net() const {
  if (type_ == SurfaceType::kBezier) return std::get<ControlNet>(data_);
  return coons::bezier_net(sum_);
}

std::vector<std::pair<std::string, const Curve*>> Surface::curves() const {
  std::vector<std::pair<std::string, const Curve*>> out;
  std::visit(
      [&](const auto& d) {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, RuledSurface>) {
          if (type_ == SurfaceType::kSectorial) {
            out = {{"curve", &d.c0}};
          } else {
            out = {{"curves[0]", &d.c0}, {"curves[1]", &d.c1}};
          }
        } else if constexpr (std::is_same_v<T, Conoid>) {
          out = {{"directrix", &d.directrix}};
        } else if constexpr (std::is_same_v<T, BoundaryCurves>) {
          out = {{"bottom", &d.bottom}, {"top", &d.top}, {"left", &d.left}, {"right", &d.right}};
        } else if constexpr (std::is_same_v<T, GeneralCoonsData>) {
          out = {{"bottom", &d.boundary.bottom}, {"top", &d.boundary.top}, {"left", &d.boundary.left},
                 {"right", &d.boundary.right},   {"du_left", &d.du_left},  {"du_right", &d.du_right},
                 {"dv_bottom", &d.dv_bottom},    {"dv_top", &d.dv_top}};
        }
      },
      data_);
  return out;
}

Surface Surface::map_curves(const std::function<Curve(const std::string&, const Curve&)>& f) const {
  switch (type_) {
    case SurfaceType::kRuled: {
      const auto& d = std::get<RuledSurface>(data_);
      return make_ruled(f("curves[0]", d.c0), f("curves[1]", d.c1));
    }
    case SurfaceType::kSectorial: {
      const auto& d = std::get<RuledSurface>(data_);
      return Surface(type_, RuledSurface{f("curve", d.c0), d.c1});
    }
    case SurfaceType::kConoid: {
      Conoid c = std::get<Conoid>(data_);
      c.directrix = f("directrix", c.directrix);
      return make_conoid(std::move(c));
    }
    case SurfaceType::kBilinearCoons:
    case SurfaceType::kHermiteCoons: {
      const auto& d = std::get<BoundaryCurves>(data_);
      return Surface(type_,
                     BoundaryCurves{f("bottom", d.bottom), f("top", d.top), f("left", d.left), f("right", d.right)});
    }
    case SurfaceType::kGeneralCoons: {
      const auto& d = std::get<GeneralCoonsData>(data_);
      const BoundaryCurves& b = d.boundary;
      return make_general_coons(GeneralCoonsData{
          BoundaryCurves{f("bottom", b.bottom), f("top", b.top), f("left", b.left), f("right", b.right)},
          f("du_left", d.du_left), f("du_right", d.du_right), f("dv_bottom", d.dv_bottom), f("dv_top", d.dv_top),
          d.twist});
    }
    default:
      return *this;
  }
}

Surface make_ruled(Curve c0, Curve c1) {
  return Surface(SurfaceType::kRuled, RuledSurface{std::move(c0), std::move(c1)});
}
Surface make_sectorial(Curve c, const Eigen::RowVector3d& apex) {
  return Surface(SurfaceType::kSectorial, sectorial_surface(std::move(c), apex));
}
Surface make_bilinear(const std::array<Eigen::RowVector3d, 4>& corners) {
  return Surface(SurfaceType::kBilinear, BilinearSurface{corners});
}
Surface make_conoid(Conoid c) { return Surface(SurfaceType::kConoid, std::move(c)); }
Surface make_coons(BoundaryCurves b, CoonsBlending blending) {
  return Surface(blending == CoonsBlending::kLinear ? SurfaceType::kBilinearCoons : SurfaceType::kHermiteCoons,
                 std::move(b));
}
Surface make_ferguson(const std::array<Eigen::RowVector3d, 4>& corners, const std::array<Eigen::RowVector3d, 4>& du,
                      const std::array<Eigen::RowVector3d, 4>& dv) {
  return Surface(SurfaceType::kFerguson, ferguson_patch(corners, du, dv));
}
Surface make_hermite16(HermitePatch h) { return Surface(SurfaceType::kHermite16, std::move(h)); }
Surface make_general_coons(GeneralCoonsData g) { return Surface(SurfaceType::kGeneralCoons, std::move(g)); }
Surface make_bezier_surface(ControlNet net) { return Surface(SurfaceType::kBezier, std::move(net)); }

FittedNet fitted_net(const Surface& s, int fit_degree) {
  assert(fit_degree >= 1);
  FittedNet out;
  if (auto net = s.bezier_net()) {
    out.net = std::move(*net);
    return out;
  }
  out.exact = false;
  out.fit_degree = fit_degree;
  const Surface approx = s.map_curves([&](const std::string& field, const Curve& c) -> Curve {
    if (c.is_polynomial()) return c;
    // The size of the curve: the diagonal of the bounding box of its fit's check points.
    Eigen::RowVector3d lo = c.at(0), hi = lo;
    for (int k = 1; k <= 32; ++k) {
      lo = lo.cwiseMin(c.at(k / 32.0));
      hi = hi.cwiseMax(c.at(k / 32.0));
    }
    const double rounding = 1e-13 * std::max(1.0, (hi - lo).norm());
    BezierFit fit;
    for (int degree = 1; degree <= fit_degree; ++degree) {
      fit = fit_bezier(c, degree);
      if (fit.max_deviation <= rounding) break;
    }
    const bool derivative = field.rfind("du_", 0) == 0 || field.rfind("dv_", 0) == 0;
    out.fits.push_back({field, fit.curve.degree(), fit.fitted_degree, fit.max_deviation, !derivative});
    if (!(fit.max_deviation <= out.max_curve_deviation)) out.max_curve_deviation = fit.max_deviation;  // NaN too
    return fit.curve;
  });
  out.net = *approx.bezier_net();
  return out;
}

}  // namespace coons
