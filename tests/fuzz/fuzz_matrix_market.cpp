// libFuzzer target: the project's Matrix Market readers (src/coons/io/matrix_market.h: sparse
// coordinate and dense array, both real general, and read_market_matrix for every real kind), fed the bytes through a
// file as `coons` reads them. An InputError is the expected answer to bad bytes; anything else is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "coons/io/input_error.h"
#include "coons/io/matrix_market.h"

namespace {

// One scratch file per process, in memory where the system has /dev/shm.
const std::string& scratch_path() {
  static const std::string path = [] {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/coons_fuzz_mm_" + std::to_string(getpid()) + ".mtx";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = scratch_path();
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    const bool complete = std::fwrite(data, 1, size, f) == size;
    std::fclose(f);
    if (!complete) return 0;
  } else {
    return 0;
  }
  try {
    (void)coons::read_matrix_market(path);
  } catch (const coons::InputError&) {
  }
  try {
    (void)coons::read_dense_matrix_market(path);
  } catch (const coons::InputError&) {
  }
  try {
    (void)coons::read_market_matrix(path);
  } catch (const coons::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
