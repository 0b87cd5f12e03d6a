// The keys of shard tasks (docs/formats.md, "Sharded studies"): FNV-1a (64 bit) as 16 lowercase
// hex digits, of a file's bytes or of the compact JSON of a task's inputs. The one hash of both
// kinds of shards (family tasks: family_tasks.h; boundary files: `coons study FILES --shard`) and
// of their tests.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace coons {

//! FNV-1a (64 bit) of `text`, as 16 lowercase hex digits.
std::string fnv1a_hex(const std::string& text);

//! A task's key: fnv1a_hex of the compact JSON (dump()) of its inputs; JSON objects sort their
//! keys, so equal inputs give equal keys.
std::string task_key(const nlohmann::json& inputs);

//! The key of task `index` of a boundary-file study whose block is `study`: the block without its
//! "files", plus "file" (files[index], the name as given) and "content" (fnv1a_hex of its bytes).
std::string files_task_key(const nlohmann::json& study, std::size_t index, const std::string& content_hash);

}  // namespace coons
