#!/usr/bin/env bash
# The sanitizer build: the library, the CLI and the tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DCOONS_SANITIZE=ON) in ./build-asan, then the fast tests (the
# default suite: no benchmarks, nothing tagged [slow], not the browser tests). Any finding fails
# its test, and the script.
# Usage: scripts/sanitize.sh [extra ctest arguments, e.g. -R parse_boundary]
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-asan
jobs=$(nproc)

# Without hypre and MPI (its test backend_hypre says "skipped" here): a bare MPI_Init/MPI_Finalize
# of Debian's Open MPI 4.1 leaves about 3,300 allocations (120 kB) that LeakSanitizer reports, most
# from plugins unloaded at finalize, whose frames no suppression by name can match short of the
# slow unwinder (fast_unwind_on_malloc=0) for the whole suite.
# Without OpenCASCADE (backend_occt says "skipped"): its libraries are not instrumented and keep
# process-lifetime singletons (message printers, the XSControl session) that LeakSanitizer would
# have to be taught; coons_cad's own code is checked by the Release suite.
# -O1: gcc's AddressSanitizer + UBSan instrumentation at -O2 made one heavy test file take 58 s to
# compile (14 s without sanitizers, 38 s at -O1). Measured 2026-11-28 from a fresh clone on 2 cores:
# this script took 39 min at -O2 and 31 min at -O1, its tests 356 s either way, 681 of 681 clean.
# CMAKE_UNITY_BUILD: CMake compiles the files of each target eight at a time as one unit, so the
# templates of Eigen, Catch2, fmt and nlohmann-json are instrumented once per unit, not once per
# file. Measured 2026-11-29 from scratch on 2 cores: 17.4 min instead of 29.1 (user 31 min instead
# of 55), 693 of 693 tests clean either way. Within a unit every anonymous-namespace name must be
# defined once, and a file's `using namespace` reaches the files after it: a clash is a compile
# error here, mended by giving the helper one definition (or a name of its own). The Release build
# (scripts/build.sh) compiles file by file, as clang-tidy and the depfiles of tidy.sh --since need.
mkdir -p "$build"
configure_log=$build/configure.log
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
      -DCMAKE_UNITY_BUILD=ON -DCOONS_SANITIZE=ON -DCOONS_BUILD_BENCHMARKS=OFF -DCOONS_WITH_HYPRE=OFF -DCOONS_WITH_OCCT=OFF >"$configure_log" 2>&1 || { cat "$configure_log" >&2; exit 1; }
grep -E "^-- coons:" "$configure_log" || true
cmake --build "$build" -j"$jobs"  # the library, the CLI, the tests and the fuzz-regression replays

# halt_on_error: the first finding ends the process with a non-zero status, so its test fails.
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
unset COONS_SLOW
# Without the browser tests (label browser): they time Chromium drawing the page, not coons, whose
# `coons view` runs in the other view tests here; under ASan they took 146 s of the 2 cores' time
# (2026-12-02, CTestCostData), and the Release suite runs them.
ctest --test-dir "$build" -j"$jobs" --output-on-failure -E '^bench_' -LE browser "$@"
