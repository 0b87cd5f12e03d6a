#!/usr/bin/env bash
# Install what is missing, build, and run the test suite (slow tests are opt-in: COONS_SLOW=1).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh >/dev/null
ctest --test-dir build --output-on-failure -j"$(nproc)"
