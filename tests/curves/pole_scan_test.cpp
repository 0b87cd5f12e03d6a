// Poles between samples (coons/curves/pole_scan.h): found where they are, and smooth curves with
// roots, steep ends and narrow bumps left alone.
#include "coons/curves/pole_scan.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>

using namespace coons;

namespace {
AnalyticCurve z_curve(const std::string& z) { return AnalyticCurve({"t", "0", z}); }
}  // namespace

TEST_CASE("find_singularity: a pole between the samples is found where it is", "[curves]") {
  // 1/pi is on no sample grid; the residue 0.001 keeps the neighbouring samples small (about 1).
  for (const char* z : {"0.001*t*(1-t)/(t-1/_pi)", "0.001/(t-1/_pi)^2", "-0.001/(t-1/_pi)^3"}) {
    INFO(z);
    std::string expr = z;
    for (std::size_t at = expr.find("_pi"); at != std::string::npos; at = expr.find("_pi")) expr.replace(at, 3, "pi");
    const auto found = find_singularity(z_curve(expr));
    REQUIRE(found);
    CHECK(found->component == 2);
    CHECK(found->s == Approx(1 / M_PI).margin(1e-9));
    CHECK_FALSE(std::abs(found->value) < 1e8);
  }
}

TEST_CASE("find_singularity: a pole of even order in the first or last sample interval is found", "[curves]") {
  // |f| peaks at the end sample itself, which the peak search used to skip
  for (const auto& [z, at] : {std::pair{"0.001/(t-0.0003)^2-0.001/0.9997^2*t", 0.0003},
                              std::pair{"0.001/(t-0.9997)^2-0.001/0.9997^2*(1-t)", 0.9997}}) {
    INFO(z);
    const auto found = find_singularity(z_curve(z));
    REQUIRE(found);
    CHECK(found->s == Approx(at).margin(1e-7));  // where |f| passed 1e8 times the curve's size
  }
}

TEST_CASE("find_singularity: a pole on a sample, where the value is huge but finite, is found there", "[curves]") {
  // tan(pi t) at t = 1/2 (sample 512 of 1024) is 1.6e16, not infinite: it had set the curve's size
  // itself, so no value ever exceeded 1e8 times that size, and `coons surface` sampled z = 1.6e16
  for (const char* z : {"tan(pi*t)", "0.001*tan(pi*t)", "1/cos(pi*t)"}) {
    INFO(z);
    const auto found = find_singularity(z_curve(z));
    REQUIRE(found);
    CHECK(found->component == 2);
    CHECK(found->s == Approx(0.5).margin(1e-9));
  }
  // on the last sample: an end sample counts as its one neighbour does (review r63a)
  for (const char* z : {"tan(pi/2*t)", "tan(pi/2*(1-t))"}) {
    INFO(z);
    const auto found = find_singularity(z_curve(z));
    REQUIRE(found);
    CHECK((found->s == 1.0 || found->s == 0.0));
  }
}

TEST_CASE("find_singularity: roots, steep ends and narrow bumps are not poles", "[curves]") {
  for (const char* z : {"sin(20*t)", "t-1/pi", "1/(t+0.01)", "exp(-1e5*(t-1/pi)^2)", "tan(1.5*t)", "(t-1/pi)^3", "0",
                        "1e-300*sin(t)", "0.01*sin(1024*pi*t)"}) {  // (the last: rounding noise at the samples)
    INFO(z);
    const auto found = find_singularity(z_curve(z));
    CHECK_FALSE(found);
  }
}
