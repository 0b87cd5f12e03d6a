#include "coons/io/net_json.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "support/fixtures.h"

using namespace coons;
using nlohmann::json;

namespace {
std::string net_text(const ControlNet& net, int level) {
  std::string text;
  write_net_json(net, level, [&text](std::string_view piece) { text.append(piece); });
  return text;
}
}  // namespace

TEST_CASE("write_net_json: reads back to the doubles of net_to_json", "[io]") {
  ControlNet net = coons::test::make_random_net(4, 6, 11);
  // numbers whose printed forms differ in kind: integral, signed zero, tiny, huge, shortest-digit cases
  const double special[] = {1.0,  -0.0,           0.0, 1e-300,  5e-324,  1e20,
                            1e15, 123456789012.0, 0.1, 1.0 / 3, -2.5e-7, std::numeric_limits<double>::max()};
  int k = 0;
  for (double x : special) net.points.data()[k++ * 5 % net.points.size()] = x;
  const std::string text = net_text(net, 1);
  const json parsed = json::parse(text);
  const json expected = json::parse(net_to_json(net).dump(2));  // the old path: nlohmann's dump
  REQUIRE(parsed.size() == 5);
  CHECK(parsed == expected);
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j)
      for (int c = 0; c < 3; ++c) {
        REQUIRE(parsed[i][j][c].is_number_float());  // integral values keep their ".0"
        REQUIRE(parsed[i][j][c].get<double>() == net.at(i, j)(c));
        REQUIRE(std::signbit(parsed[i][j][c].get<double>()) == std::signbit(net.at(i, j)(c)));
      }
  CHECK(text.find("\n    [\n      [") != std::string::npos);  // rows, then one point per line
}

TEST_CASE("write_net_json: a large net arrives in pieces of about 1 MiB", "[io]") {
  const ControlNet net = coons::test::make_random_net(200, 200, 5);
  std::size_t pieces = 0, largest = 0;
  std::string text;
  write_net_json(net, 0, [&](std::string_view piece) {
    ++pieces;
    largest = std::max(largest, piece.size());
    text.append(piece);
  });
  CHECK(pieces > 1);
  CHECK(largest < (std::size_t(1) << 20) + 4096);
  CHECK(json::parse(text) == json::parse(net_to_json(net).dump()));
}
