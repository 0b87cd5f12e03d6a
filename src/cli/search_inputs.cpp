#include "search_inputs.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/net/coons_net.h"
#include "coons/study/backend_choice.h"
#include "coons/study/target.h"

namespace coons::cli {

namespace {

std::vector<double> numbers_after_colon(const std::string& spec, size_t count) {
  std::vector<double> out;
  std::stringstream in(spec.substr(spec.find(':') + 1));
  for (std::string item; std::getline(in, item, ',');) {
    // strtod, not stod: stod refuses a value that underflows (1e-320, a subnormal) as out of range
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
      throw InputError("command line", "--target", "'" + item + "' is not a finite number");
    // (but one that reads as 0 without being written as 0 lies below the smallest double)
    if (x == 0 && !zero_digits(item))
      throw InputError("command line", "--target",
                       "'" + item + "' is below the smallest double and would be read as 0");
    if (const std::string why = coordinate_problem(x); !why.empty())
      throw InputError("command line", "--target", fmt::format("'{}' {}", item, why));
    out.push_back(x);
  }
  if (out.size() != count)
    throw InputError("command line", "--target", fmt::format("'{}' needs {} numbers after the colon", spec, count));
  return out;
}

}  // namespace

std::optional<Target> resolve_target(const std::string& spec, const std::string& boundary_path, const Boundary& b,
                                     int samples) {
  std::optional<Target> t;
  if (spec.empty()) {
    t = read_boundary_target(boundary_path, samples);
  } else if (spec == "hermite-coons" || spec == "coons") {
    if (spec == "hermite-coons" && (b.m < 3 || b.n < 3))
      throw InputError(boundary_path, "degree", "--target hermite-coons needs degree >= 3 in both directions");
    t = Target{};
    t->net = spec == "coons" ? discrete_coons_net(b) : hermite_coons_net(b);
  } else if (spec.rfind("sphere:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 4);
    t = Target{Target::Kind::kSphere, {}, {v[0], v[1], v[2]}, {0, 0, 1}, v[3], samples};
  } else if (spec.rfind("cylinder:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 7);
    t = Target{Target::Kind::kCylinder, {}, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], samples};
  } else if (spec.rfind("plane:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 6);
    t = Target{Target::Kind::kPlane, {}, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, 1, samples};
  } else {
    const BoundaryFile f = read_boundary_file(spec);
    if (!f.net) throw InputError(spec, "net", "a target file must hold a \"net\"");
    t = Target{};
    t->net = *f.net;
  }
  if (t && !spec.empty()) {  // the numbers of --target (a file's were checked as they were read)
    if (!normalise_target_direction(*t)) throw InputError("command line", "--target", kNoTargetDirection);
    if ((t->kind == Target::Kind::kSphere || t->kind == Target::Kind::kCylinder) && !(t->radius > 0))
      throw InputError("command line", "--target", "radius must be positive");
  }
  if (t) t->samples = samples;
  return t;
}

void require_search_backend(const solvers::SolverInfo* requested, const Boundary& boundary, bool indefinite,
                            const std::string& where) {
  if (!requested) return;
  if (const SearchBackendCheck check = check_search_backend(*requested, boundary, indefinite); !check.applicable)
    throw InputError("command line", "--solver",
                     where.empty() ? check.reason : fmt::format("{} (on {})", check.reason, where));
}

const char* const kBSplineNeedsMatrix =
    "the non-uniform mask system of a B-spline boundary is an assembled matrix (a direct or iterative backend: "
    "eigen-ldlt, eigen-lu, cg, gmres, ...)";

const solvers::SolverInfo* require_matrix_backend(const solvers::SolverInfo* requested, const std::string& needs) {
  if (requested && !solvers::accepts_matrix(*requested))
    throw InputError("command line", "--solver", requested->name + " works from the grid stencil only; " + needs);
  return requested;
}

void require_weight_search_backend(const solvers::SolverInfo* requested) {
  if (!requested) return;
  if (const SearchBackendCheck check = check_weight_search_backend(*requested); !check.applicable)
    throw InputError("command line", "--solver", check.reason);
}

}  // namespace coons::cli
