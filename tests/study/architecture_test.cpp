// The layering of docs/architecture.md holds in the includes: each layer of src/coons includes
// only itself and the layers below it (the same as its CMake target links), solvers/ includes no
// coons header but the generated config, and nothing in the library includes the command line.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

namespace fs = std::filesystem;

namespace {

const fs::path kSource = fs::path(COONS_DATA_DIR).parent_path();

std::vector<std::pair<fs::path, std::string>> includes_under(const fs::path& folder) {
  std::vector<std::pair<fs::path, std::string>> out;
  const std::regex include(R"(^\s*#\s*include\s*\"([^\"]+)\")");
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".h" && ext != ".cpp" && ext != ".in") continue;
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, include)) out.emplace_back(entry.path(), m[1].str());
    }
  }
  return out;
}

}  // namespace

TEST_CASE("architecture: every layer of the library includes only itself and the layers below it", "[study]") {
  const std::map<std::string, std::set<std::string>> allowed = {
      {"net", {"net"}},
      {"mask", {"net", "mask"}},
      {"metrics", {"net", "mask", "metrics"}},
      {"curves", {"net", "curves"}},
      {"surfaces", {"net", "curves", "surfaces"}},
      {"io", {"net", "mask", "metrics", "curves", "surfaces", "tri", "io"}},
      {"alpha", {"net", "mask", "metrics", "alpha"}},
      {"tri", {"net", "mask", "metrics", "tri"}},
      {"study", {"net", "mask", "metrics", "curves", "surfaces", "tri", "io", "alpha", "study"}},
      {"cad", {"net", "mask", "metrics", "curves", "surfaces", "tri", "io", "cad"}},  // optional (OpenCASCADE)
  };
  const std::regex coons_header(R"(^coons/([a-z_]+)/)");
  int checked = 0;
  for (const auto& [layer, may] : allowed) {
    for (const auto& [file, header] : includes_under(kSource / "src" / "coons" / layer)) {
      std::smatch m;
      if (!std::regex_search(header, m, coons_header)) continue;  // same folder, solvers/, coons/config.h
      INFO(file.string() << " includes " << header);
      CHECK(may.count(m[1].str()) == 1);
      ++checked;
    }
  }
  CHECK(checked > 50);
  for (const auto& [file, header] : includes_under(kSource / "solvers")) {
    INFO(file.string() << " includes " << header);
    CHECK((header.rfind("coons/", 0) != 0 || header == "coons/config.h"));
  }
  for (const auto& [file, header] : includes_under(kSource / "src" / "coons")) {
    INFO(file.string() << " includes " << header);
    CHECK(header.find("cli/") == std::string::npos);
  }
}
