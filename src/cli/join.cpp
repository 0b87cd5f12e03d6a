// `coons join A.json SIDE B.json SIDE`: the C⁰ gap and the largest angle between the tangent
// planes along the seam where side A of one surface meets side B of another (LN1, LN2).
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/surface_io.h"
#include "coons/surfaces/joining.h"
#include "registry.h"

namespace coons::cli {

namespace {

struct JoinRequest {
  std::string first, first_side, second, second_side;
  bool reversed = false;
  int samples = 101;
};

int run_join(const JoinRequest& r) {
  auto side = [](const std::string& name, const char* field) {
    if (name == "bottom") return Side::kBottom;
    if (name == "top") return Side::kTop;
    if (name == "left") return Side::kLeft;
    if (name == "right") return Side::kRight;
    throw InputError("command line", field, "'" + name + "' is not bottom, top, left or right");
  };
  const Side a_side = side(r.first_side, "FIRST_SIDE"), b_side = side(r.second_side, "SECOND_SIDE");
  if (r.samples < 2 || r.samples > 1000000)
    throw InputError("command line", "--samples", "must be between 2 and 1000000");
  SurfaceReadOptions options;
  options.min_model_size = kMinModelSize;  // the gap and angle of a model below it: surface_io.h
  const SurfaceFile a = read_surface_file(r.first, options), b = read_surface_file(r.second, options);
  const SeamReport seam = compare_seam(a.surface, a_side, b.surface, b_side, r.reversed, r.samples);
  // The reader checks expressions at 65 samples; a pole or NaN between them may meet the seam.
  if (seam.not_finite != 0)
    throw InputError(seam.not_finite == 1 ? r.first : r.second, seam.not_finite == 1 ? r.first_side : r.second_side,
                     fmt::format("the surface is not finite on this side at t = {:.6g} (a pole, or a NaN between the "
                                 "samples the reader checks)",
                                 seam.not_finite_at));
  // the scale of the gap: the bounding-box diagonal of both patches sampled on a 9 × 9 grid (the
  // files' own `size` is set only for the types whose reader checks corners with it)
  Eigen::RowVector3d lo = a.surface.at(0, 0), hi = lo;
  for (const Surface* s : {&a.surface, &b.surface})
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        const Eigen::RowVector3d p = s->at(i / 8.0, j / 8.0);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  const double size = std::max((hi - lo).norm(), 1e-300);
  const bool compared = seam.normals_compared > 0;
  nlohmann::json out = {
      {"first", a.name},
      {"second", b.name},
      {"samples", seam.samples},
      {"c0_gap", seam.c0_gap},
      // no angle, and no place of it, without a single pair of normals to compare
      {"max_normal_angle_rad", compared ? nlohmann::json(seam.max_normal_angle) : nlohmann::json()},
      {"max_normal_angle_deg", compared ? nlohmann::json(seam.max_normal_angle * 180 / M_PI) : nlohmann::json()},
      {"at", compared ? nlohmann::json(seam.at) : nlohmann::json()},
      {"normals_compared", seam.normals_compared},
      {"c0", seam.c0_gap <= 1e-9 * size},
      // no G1 claim without a single pair of normals to compare
      {"g1", seam.c0_gap <= 1e-9 * size && seam.normals_compared > 0 && seam.max_normal_angle <= 1e-6}};
  print_json(out);
  return kExitOk;
}

}  // namespace

void register_join(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<JoinRequest>();
  JoinRequest& r = *request;
  auto* cmd = app.add_subcommand("join", "C0 gap and G1 angle along the seam of two surfaces (surface JSON files)");
  cmd->add_option("FIRST", r.first, "first surface description")->required();
  cmd->add_option("FIRST_SIDE", r.first_side, "bottom | top | left | right")->required();
  cmd->add_option("SECOND", r.second, "second surface description")->required();
  cmd->add_option("SECOND_SIDE", r.second_side, "bottom | top | left | right")->required();
  cmd->add_flag("--reversed", r.reversed, "the second side runs the other way along the seam");
  cmd->add_option("--samples", r.samples, "seam samples")->capture_default_str();
  set_example(*cmd, "coons join data/surfaces/join_hermite_a.json right data/surfaces/join_hermite_b.json left");
  registry.add(cmd, [request] { return run_join(*request); });
}

}  // namespace coons::cli
