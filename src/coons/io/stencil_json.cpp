#include "stencil_json.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "coons/io/input_error.h"

namespace coons {

namespace {

std::string index_field(const std::string& name, std::size_t r) { return name + "[" + std::to_string(r) + "]"; }
std::string index_field(const std::string& name, std::size_t r, std::size_t c) {
  return index_field(name, r) + "[" + std::to_string(c) + "]";
}

std::string number_text(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

}  // namespace

Stencil stencil_from_json(const nlohmann::json& doc, const std::string& file) {
  if (!doc.is_object()) throw InputError(file, "", "a stencil file is a JSON object with \"weights\"");
  if (!doc.contains("weights")) throw InputError(file, "weights", "missing");
  const nlohmann::json& w = doc.at("weights");
  if (!w.is_array() || (w.size() != 3 && w.size() != 5))
    throw InputError(
        file, "weights",
        "must be an array of 3 or 5 rows" + (w.is_array() ? ", got " + std::to_string(w.size()) : std::string()));
  const std::size_t k = w.size(), R = k / 2;
  Eigen::MatrixXd raw = Eigen::MatrixXd::Zero(Eigen::Index(k), Eigen::Index(k));
  bool centre_given = false;
  for (std::size_t r = 0; r < k; ++r) {
    const nlohmann::json& row = w[r];
    if (!row.is_array() || row.size() != k)
      throw InputError(file, index_field("weights", r), "must be an array of " + std::to_string(k) + " numbers");
    for (std::size_t c = 0; c < k; ++c) {
      const nlohmann::json& x = row[c];
      if (r == R && c == R && x.is_null()) continue;
      if (!x.is_number() || !std::isfinite(x.get<double>()))
        throw InputError(
            file, index_field("weights", r, c),
            r == R && c == R ? "must be a number or null (the centre is implied)" : "must be a finite number");
      if (r == R && c == R) centre_given = true;
      raw(Eigen::Index(r), Eigen::Index(c)) = x.get<double>();
    }
  }
  const double given_centre = raw(Eigen::Index(R), Eigen::Index(R));
  raw(Eigen::Index(R), Eigen::Index(R)) = 0;
  const double scale = raw.cwiseAbs().maxCoeff();
  for (std::size_t r = 0; r < k; ++r)
    for (std::size_t c = 0; c < k; ++c) {
      const double a = raw(Eigen::Index(r), Eigen::Index(c)), b = raw(Eigen::Index(k - 1 - r), Eigen::Index(k - 1 - c));
      if (std::abs(a - b) > 1e-12 * scale)
        throw InputError(file, index_field("weights", r, c),
                         "breaks the symmetry W(a, b) = W(-a, -b): " + number_text(a) + " here, " + number_text(b) +
                             " at " + index_field("weights", k - 1 - r, k - 1 - c));
    }
  // Within that tolerance, each pair is made its mean: a stencil accepted as symmetric is symmetric
  // (the Cholesky-type backends read one triangle of the matrix); an exactly symmetric one is unchanged.
  // Summed in units of the largest weight: weights near the largest double would overflow the
  // sum (the stencil is the same whatever the units: make_stencil divides by the centre).
  if (scale > 0) raw /= scale;
  raw = (0.5 * (raw + raw.reverse())).eval();
  const double centre = -raw.sum();
  if (!(std::abs(centre) > 1e-12))
    throw InputError(file, "weights", "the weights around the centre sum to 0, so the implied centre is 0");
  const double given = given_centre / scale;  // finite unless the centre dwarfs every other weight
  if (centre_given && given_centre != 0 && !(std::abs(given - centre) <= 1e-9 * std::max(1.0, std::abs(centre))))
    throw InputError(file, index_field("weights", R, R),
                     "the centre is implied by the others (the weights sum to 0): write null, 0 or " +
                         number_text(centre * scale) + ", not " + number_text(given_centre));
  raw(Eigen::Index(R), Eigen::Index(R)) = centre;
  return make_stencil(raw);
}

FreeGrid free_grid_from_json(const nlohmann::json& free, int m, int n, const std::string& file) {
  if (!free.is_array() || free.size() != static_cast<std::size_t>(m) + 1)
    throw InputError(file, "free",
                     "must be an array of " + std::to_string(m + 1) + " rows (the shape of net)" +
                         (free.is_array() ? ", got " + std::to_string(free.size()) : std::string()));
  FreeGrid grid(m + 1, n + 1);
  for (std::size_t i = 0; i < free.size(); ++i) {
    const nlohmann::json& row = free[i];
    if (!row.is_array() || row.size() != static_cast<std::size_t>(n) + 1)
      throw InputError(file, index_field("free", i), "must be an array of " + std::to_string(n + 1) + " values 0 or 1");
    for (std::size_t j = 0; j < row.size(); ++j) {
      const nlohmann::json& x = row[j];
      const bool ok = x.is_boolean() || (x.is_number_integer() && (x.get<long long>() == 0 || x.get<long long>() == 1));
      if (!ok)
        throw InputError(file, index_field("free", i, j),
                         "must be 0 or 1 (an integer, or true/false), not " + x.dump());
      grid(Eigen::Index(i), Eigen::Index(j)) = x.is_boolean() ? x.get<bool>() : x.get<long long>() == 1;
    }
  }
  return grid;
}

void require_valid_problem(const StencilProblem& problem, const Stencil& stencil, const std::string& file,
                           const ProblemCheckOptions& options) {
  const auto issues = check_stencil_problem(problem, stencil, options);
  if (!issues.empty()) throw InputError(file, issues.front().field, issues.front().reason);
}

}  // namespace coons
