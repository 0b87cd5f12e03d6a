#include "coons/surfaces/bspline_sampling.h"

namespace coons {

SurfacePoint bspline_surface_point(const BSplineSurface& surface, double s, double t) {
  const double u0 = surface.knots_u(0), u1 = surface.knots_u(surface.knots_u.size() - 1);
  const double v0 = surface.knots_v(0), v1 = surface.knots_v(surface.knots_v.size() - 1);
  const double u = u0 + s * (u1 - u0), v = v0 + t * (v1 - v0);
  const double su = u1 - u0, sv = v1 - v0;  // d/ds = su d/du
  SurfacePoint p;
  p.p = evaluate_derivative(surface, 0, 0, u, v);
  p.du = su * evaluate_derivative(surface, 1, 0, u, v);
  p.dv = sv * evaluate_derivative(surface, 0, 1, u, v);
  p.duu = su * su * evaluate_derivative(surface, 2, 0, u, v);
  p.duv = su * sv * evaluate_derivative(surface, 1, 1, u, v);
  p.dvv = sv * sv * evaluate_derivative(surface, 0, 2, u, v);
  return p;
}

SurfaceSamples sample_bspline_grid(const BSplineSurface& surface, int k) {
  return sample_grid([&surface](double s, double t) { return bspline_surface_point(surface, s, t); }, k);
}

}  // namespace coons
