// The keys of shard tasks (coons/study/task_key.h): FNV-1a (64 bit) as docs/formats.md names it,
// pinned to the published test vectors, and the files study's key over its documented inputs.
#include "coons/study/task_key.h"

#include <catch2/catch.hpp>

using namespace coons;
using nlohmann::json;

TEST_CASE("fnv1a_hex: the published FNV-1a 64-bit test vectors") {
  CHECK(fnv1a_hex("") == "cbf29ce484222325");
  CHECK(fnv1a_hex("a") == "af63dc4c8601ec8c");
  CHECK(fnv1a_hex("foobar") == "85944171f73967e8");
}

TEST_CASE("files_task_key: the study block without its file list, with the file and its content") {
  const json study = {{"inputs", "files"}, {"files", {"a.json", "b.json"}}, {"degrees", {3, 4}}};
  const std::string key = files_task_key(study, 1, "0123456789abcdef");
  CHECK(key ==
        task_key({{"inputs", "files"}, {"degrees", {3, 4}}, {"file", "b.json"}, {"content", "0123456789abcdef"}}));
  CHECK(key != files_task_key(study, 0, "0123456789abcdef"));
  CHECK(key != files_task_key(study, 1, "0123456789abcdee"));
  json other = study;
  other["files"] = {"c.json", "b.json"};  // another file list, the same task
  CHECK(files_task_key(other, 1, "0123456789abcdef") == key);
  other["degrees"] = {3};
  CHECK(files_task_key(other, 1, "0123456789abcdef") != key);
}
