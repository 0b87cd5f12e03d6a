// The `coons` command line (docs/formats.md is its contract). Exit status: 0 success, 2 bad input
// (one `error:` line on stderr, nothing written), 3 a solver failed (the report says why).
#pragma once

namespace coons::cli {

int run(int argc, char** argv);

}  // namespace coons::cli
