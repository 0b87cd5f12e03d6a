// coons_make_step OUT_DIR: writes the sample STEP files of data/cad/ (scripts/make_step.sh):
//   bspline_patch.step  one face, the Greville Coons surface of cad_sample_boundary() (its four
//                       edges are the boundary's B-spline curves);
//   four_edges.step     the four curves as free edges, shuffled and partly reversed:
//                       edge 0 = right, edge 1 = bottom reversed, edge 2 = left, edge 3 = top reversed.
#include <cstdio>
#include <exception>
#include <string>

#include "cad_fixtures.h"
#include "coons/cad/cad_surface.h"
#include "coons/io/write_files.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: coons_make_step OUT_DIR\n");
    return 2;
  }
  try {
    const std::string dir = argv[1];
    const coons::BSplineBoundary b = coons::test::cad_sample_boundary();
    const coons::BSplineSurface s = coons::greville_coons_surface(b);
    auto reversed = [](coons::BSplineCurve c) {
      c.points = c.points.colwise().reverse().eval();
      const double a = c.start(), e = c.end();
      c.knots = (a + e - c.knots.reverse().array()).matrix().eval();  // eval: no aliasing
      return c;
    };
    coons::write_file_atomically(dir + "/bspline_patch.step", [&](std::ostream& o) {
      coons::cad::write_step_surface(o, s, "bspline_patch.step", "sample", coons::test::kCadSampleTimeStamp);
    });
    coons::write_file_atomically(dir + "/four_edges.step", [&](std::ostream& o) {
      coons::cad::write_step_edges(o, {b.right, reversed(b.bottom), b.left, reversed(b.top)}, "four_edges.step",
                                   "sample", coons::test::kCadSampleTimeStamp);
    });
    std::printf("%s/bspline_patch.step\n%s/four_edges.step\n", dir.c_str(), dir.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
