#include "coons/study/study_failures.h"

#include <fmt/format.h>

#include <cmath>

namespace coons {

namespace {

std::string search_phrase(const std::string& what, const AlphaSearchSummary& s) {
  return fmt::format("{} {}", what, to_string(s.status));
}

// The file of the shape called `boundary` (degree cells and reference tables carry the name only).
std::string file_of(const StudyResult& r, const std::string& boundary) {
  for (const ShapeEntry& shape : r.shapes)
    if (shape.boundary.name == boundary) return shape.file;
  return "";
}

}  // namespace

bool search_failed(const AlphaSearchSummary& s) {
  return s.status == SearchStatus::kSolverFailed || s.status == SearchStatus::kFailedRegion ||
         s.status == SearchStatus::kNotApplicable;
}

std::vector<std::string> shape_failures(const ShapeEntry& shape) {
  std::vector<std::string> out;
  for (const ShapeOptimum& o : shape.optima) {
    if (search_failed(o.alpha)) out.push_back(search_phrase(o.objective + ": α*", o.alpha));
    if (search_failed(o.mu)) out.push_back(search_phrase(o.objective + ": μ*", o.mu));
    if (o.weight && search_failed(*o.weight)) out.push_back(search_phrase(o.objective + ": w*", *o.weight));
    if (!std::isfinite(o.coons)) out.push_back(o.objective + ": the solve at α = −1/4 failed");
    if (!std::isfinite(o.laplace)) out.push_back(o.objective + ": the solve at α = 0 failed");
  }
  int curves = 0;
  for (const SweepRow& row : shape.curves) curves += row.summary.ok() ? 0 : 1;
  if (curves > 0) out.push_back(fmt::format("{} of {} energy-curve solves failed", curves, shape.curves.size()));
  return out;
}

std::vector<StudyFailure> study_failures(const StudyResult& r) {
  std::vector<StudyFailure> out;
  for (const ShapeEntry& shape : r.shapes)
    for (const std::string& what : shape_failures(shape))
      out.push_back({shape.file, shape.boundary.name + ": " + what});
  for (const DegreeLawEntry& law : r.laws)
    for (const DegreeCell& c : law.cells)
      for (const auto& [name, s] : {std::pair{"α*", &c.alpha}, std::pair{"μ*", &c.mu}})
        if (search_failed(*s))
          out.push_back(
              {file_of(r, law.boundary),
               search_phrase(fmt::format("{}: {} at degree {}: {}", law.boundary, law.objective, c.degree, name), *s)});
  for (const ReferenceTable& t : r.references) {
    for (const ReferenceRow& row : t.rows)
      if (!std::isfinite(row.center_z))
        out.push_back(
            {file_of(r, t.boundary), fmt::format("{}: the reference row at α = {} failed", t.boundary, row.alpha)});
    if (search_failed(t.best))
      out.push_back({file_of(r, t.boundary), search_phrase(t.boundary + ": the best fit to the target", t.best)});
  }
  for (const TriStudyEntry& e : r.triangles)
    for (const TriStudyRow& row : e.rows)
      for (const TriStudyCell& c : row.cells) {
        const std::string where = fmt::format("{}: {} at degree {}", e.boundary.name, row.objective, c.degree);
        if (search_failed(c.c)) out.push_back({e.file, search_phrase(where + ": c*", c.c)});
        if (!std::isfinite(c.quadratic)) out.push_back({e.file, where + ": the solve at c = −1/6 failed"});
        if (!std::isfinite(c.laplace)) out.push_back({e.file, where + ": the solve at c = 0 failed"});
      }
  return out;
}

std::vector<StudyFailure> bspline_study_failures(const std::vector<BSplineStudyRow>& rows) {
  std::vector<StudyFailure> out;
  for (const BSplineStudyRow& row : rows) {
    if (!std::isfinite(row.thin_plate_coons))
      out.push_back({row.file, row.name + ": the B-spline net at α = −1/4 failed"});
    if (!std::isfinite(row.thin_plate_laplace))
      out.push_back({row.file, row.name + ": the B-spline net at α = 0 failed"});
    for (const auto& [objective, s] : row.searches)
      if (search_failed(s)) out.push_back({row.file, search_phrase(row.name + ": " + objective + ": best α", s)});
  }
  return out;
}

std::vector<StudyFailure> family_failures(const AlphaFamilyResult& r) {
  std::vector<StudyFailure> out;
  const std::string family = r.options.family_name();
  for (const AlphaFamilyCell& c : r.cells) {
    const std::string where = fmt::format("{}: {} at degree {}", family, c.objective, c.degree);
    if (c.failed > 0)
      out.push_back({"", fmt::format("{}: {} of {} α* searches failed", where, c.failed, c.alpha_star.size())});
    if (c.grid_failed > 0)
      out.push_back({"", fmt::format("{}: {} evaluations on the best-single-α grid failed", where, c.grid_failed)});
  }
  return out;
}

}  // namespace coons
