// Energies of nets far from unit size, evaluated on the net scaled by a power of two. Every energy
// of coons is a quadratic form of the net's points (each form bilinear in its two nets), and a
// power of two scales exactly, so E(2^k X) = 4^k E(X) up to the final ldexp. A net whose largest
// |coordinate| has a binary exponent k outside [−kScaleFreeExponent, kScaleFreeExponent] is
// evaluated as net·2^−k and the result multiplied by 2^k per net; inside that range (about
// 1e±90) no product of an evaluation underflows or overflows, so scaling would give the same bits
// and the net is used as it is, without a copy. (A model of 1e−160 had subnormal products: its
// twist energy came out 1.6 % off.) Net: ControlNet or tri::TriNet (a `points` matrix).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdlib>

namespace coons {

constexpr int kScaleFreeExponent = 300;

//! k when the largest |coordinate| of net is 2^k·[1, 2) with |k| > kScaleFreeExponent, else 0.
template <class Net>
int energy_scale_exponent(const Net& net) {
  const double top = net.points.size() > 0 ? net.points.cwiseAbs().maxCoeff() : 0.0;
  if (!(top > 0) || !std::isfinite(top)) return 0;
  const int k = std::ilogb(top);
  return std::abs(k) > kScaleFreeExponent ? k : 0;
}

//! net with every coordinate times 2^e (exact while nothing leaves the normal range).
template <class Net>
Net times_power_of_two(Net net, int e) {
  for (Eigen::Index q = 0; q < net.points.size(); ++q) net.points.data()[q] = std::ldexp(net.points.data()[q], e);
  return net;
}

//! form(X, Y), a bilinear form of two nets (the same object for an energy), evaluated on nets
//! brought into range.
template <class Net, class Form>
double scaled_form(const Net& X, const Net& Y, Form&& form) {
  const int kx = energy_scale_exponent(X), ky = &X == &Y ? kx : energy_scale_exponent(Y);
  if (kx == 0 && ky == 0) return form(X, Y);
  const Net xs = times_power_of_two(X, -kx);
  if (&X == &Y) return std::ldexp(form(xs, xs), 2 * kx);
  return std::ldexp(form(xs, times_power_of_two(Y, -ky)), kx + ky);
}

//! energy(net), a quadratic form of one net, evaluated on the net brought into range.
template <class Net, class Energy>
double scaled_energy(const Net& net, Energy&& energy) {
  return scaled_form(net, net, [&](const Net& x, const Net& /*same*/) { return energy(x); });
}

}  // namespace coons
