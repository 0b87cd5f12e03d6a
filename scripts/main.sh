#!/usr/bin/env bash
# The main job on the bundled data: install what is missing, build, solve every boundary in
# data/boundaries as Coons net and at alpha in {-0.25, -0.1, 0}; results in out/main/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh >/dev/null
./build/coons batch data/boundaries --out out/main
