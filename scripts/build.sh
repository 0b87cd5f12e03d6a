#!/usr/bin/env bash
# Configures and builds coons (Release) in ./build. Extra arguments go to CMake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >build.configure.log 2>&1 || { cat build.configure.log >&2; exit 1; }
grep -E "^-- coons:" build.configure.log || true
cmake --build build -j"$(nproc)"
