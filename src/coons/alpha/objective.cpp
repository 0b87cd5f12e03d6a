#include "objective.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "coons/net/bernstein.h"

namespace coons {

double target_distance(const Target& t, const Eigen::RowVector3d& p, Eigen::RowVector3d* gradient,
                       Eigen::Matrix3d* hessian) {
  if (hessian) hessian->setZero();
  switch (t.kind) {
    case Target::Kind::kSphere: {
      const Eigen::RowVector3d d = p - t.point;
      const double r = d.norm();
      const Eigen::RowVector3d n = r > 0 ? Eigen::RowVector3d(d / r) : Eigen::RowVector3d::Zero();
      if (gradient) *gradient = n;
      if (hessian && r > 0) *hessian = (Eigen::Matrix3d::Identity() - n.transpose() * n) / r;
      return r - t.radius;
    }
    case Target::Kind::kCylinder: {
      const Eigen::RowVector3d axis = t.direction.normalized();
      Eigen::RowVector3d q = p - t.point;
      q -= q.dot(axis) * axis;
      const double r = q.norm();
      const Eigen::RowVector3d n = r > 0 ? Eigen::RowVector3d(q / r) : Eigen::RowVector3d::Zero();
      if (gradient) *gradient = n;
      if (hessian && r > 0) *hessian = (Eigen::Matrix3d::Identity() - axis.transpose() * axis - n.transpose() * n) / r;
      return r - t.radius;
    }
    case Target::Kind::kPlane: {
      const Eigen::RowVector3d normal = t.direction.normalized();
      if (gradient) *gradient = normal;
      return (p - t.point).dot(normal);
    }
    case Target::Kind::kNet:
      break;
  }
  if (gradient) gradient->setZero();
  return 0;
}

namespace {

// Mean squared distance and its derivative along dN (at the same samples).
std::pair<double, double> mean_square_distance(const ControlNet& N, const ControlNet* dN, const Target& t) {
  const int k = t.samples;
  const Eigen::MatrixX3d S = sample_surface(N, k, k);
  const Eigen::MatrixX3d dS = dN ? sample_surface(*dN, k, k) : Eigen::MatrixX3d::Zero(S.rows(), 3);
  double msd = 0, dmsd = 0;
  if (t.kind == Target::Kind::kNet) {
    const Eigen::MatrixX3d T = sample_surface(t.net, k, k);
    const Eigen::MatrixX3d D = S - T;
    msd = D.squaredNorm() / S.rows();
    dmsd = 2 * D.cwiseProduct(dS).sum() / S.rows();
  } else {
    for (Eigen::Index r = 0; r < S.rows(); ++r) {
      Eigen::RowVector3d g;
      const double d = target_distance(t, S.row(r), &g);
      msd += d * d;
      dmsd += 2 * d * g.dot(dS.row(r));
    }
    msd /= S.rows();
    dmsd /= S.rows();
  }
  return {msd, dmsd};
}

}  // namespace

double rms_distance(const ControlNet& net, const Target& target) {
  return std::sqrt(mean_square_distance(net, nullptr, target).first);
}

std::optional<Objective> parse_objective(const std::string& text, std::string* why) {
  Objective out;
  out.name = text;
  if (!text.empty() && text.back() == '+') {  // getline yields no empty last term for it
    if (why) *why = "'" + text + "' ends with '+': a term is missing";
    return std::nullopt;
  }
  std::stringstream in(text);
  std::string term;
  bool any = false;
  while (std::getline(in, term, '+')) {
    double weight = 1;
    std::string name = term;
    if (const auto star = term.find('*'); star != std::string::npos) {
      try {
        size_t used = 0;
        weight = std::stod(term.substr(0, star), &used);
        if (used != star) throw std::invalid_argument("trailing");
      } catch (const std::out_of_range&) {  // a number, beyond a double (1e400) or below its normal range (1e-320)
        if (why) *why = "weights must lie in [1e-60, 1e60], so that the values stay finite ('" + term + "')";
        return std::nullopt;
      } catch (const std::exception&) {
        if (why) *why = "'" + term + "' is not WEIGHT*NAME";
        return std::nullopt;
      }
      name = term.substr(star + 1);
    }
    if (!(std::isfinite(weight) && weight > 0)) {
      if (why) *why = "weights must be positive numbers ('" + term + "')";
      return std::nullopt;
    }
    if (!(weight >= kMinObjectiveWeight && weight <= kMaxObjectiveWeight)) {
      if (why) *why = "weights must lie in [1e-60, 1e60], so that the values stay finite ('" + term + "')";
      return std::nullopt;
    }
    std::vector<EnergyTerm> terms;
    if (name == "thin_plate")
      terms = thin_plate_terms();
    else if (name == "twist")
      terms = twist_terms();
    else if (name == "dirichlet")
      terms = dirichlet_terms();
    else if (name == "e3")
      terms = e3_terms();
    else if (name == "target")
      out.target_weight += weight;
    else if (name == "discrete_twist")
      out.discrete.emplace_back(DiscreteEnergy::kTwist, weight);
    else if (name == "discrete_dirichlet")
      out.discrete.emplace_back(DiscreteEnergy::kDirichlet, weight);
    else if (name == "discrete_thin_plate")
      out.discrete.emplace_back(DiscreteEnergy::kThinPlate, weight);
    else {
      if (why)
        *why = "unknown objective '" + name +
               "' (thin_plate, twist, dirichlet, e3, target, discrete_twist, discrete_dirichlet, discrete_thin_plate, "
               "or weighted sums)";
      return std::nullopt;
    }
    for (EnergyTerm t : terms) {
      t.weight *= weight;
      out.energy.push_back(t);
    }
    any = true;
  }
  if (!any) {
    if (why) *why = "empty objective";
    return std::nullopt;
  }
  return out;
}

ObjectiveValue evaluate_objective(const Objective& objective, const ControlNet& N, const ControlNet& dN) {
  ObjectiveValue v;
  if (!objective.energy.empty()) {
    v.value = combined_energy(N, objective.energy);
    v.derivative = 2 * combined_energy_form(N, dN, objective.energy);
  }
  for (const auto& [kind, weight] : objective.discrete) {
    v.value += weight * discrete_energy_form(N, N, kind);
    v.derivative += 2 * weight * discrete_energy_form(N, dN, kind);
  }
  if (objective.target_weight > 0 && objective.target) {
    const auto [msd, dmsd] = mean_square_distance(N, &dN, *objective.target);
    const double rms = std::sqrt(msd);
    v.value += objective.target_weight * rms;
    v.derivative += objective.target_weight * (rms > 0 ? dmsd / (2 * rms) : 0.0);
  }
  v.value = std::max(v.value, 0.0);  // a sum of squares (positive weights): below 0 only by rounding
  return v;
}

}  // namespace coons
