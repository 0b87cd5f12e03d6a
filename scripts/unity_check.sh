#!/usr/bin/env bash
# The unity build of scripts/sanitize.sh, compiled only: every target in units of eight files, as
# CMAKE_UNITY_BUILD makes them, at -O0 and without sanitizers (./build-unity; about 5 min on 2 cores
# from scratch, against 17 for sanitize.sh's build). In a unit a file's `using namespace` reaches
# the files after it and anonymous-namespace names must be defined once: CI failed on that at
# c832c4b (`test::` named two namespaces), which the Release build, file by file, cannot see.
# Usage: scripts/unity_check.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-unity
mkdir -p "$build"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g0" -DCMAKE_UNITY_BUILD=ON \
      -DCOONS_SANITIZE=OFF -DCOONS_BUILD_BENCHMARKS=OFF -DCOONS_WITH_HYPRE=OFF -DCOONS_WITH_OCCT=OFF \
      >"$build/configure.log" 2>&1 || { cat "$build/configure.log" >&2; exit 1; }
cmake --build "$build" -j"$(nproc)" -- -k
echo "unity_check: every unit compiled"
