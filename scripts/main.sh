#!/usr/bin/env bash
# The main job on the bundled data: install what is missing, build, and run the α study over
# every boundary in data/boundaries and every triangle in data/triangles at degrees 3, 4, 6, 8,
# 12, 16 (triangles: the best c of the triangular family). The report is
# out/study/report.md (figures in out/study/figures/, numbers in out/study/results.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh >/dev/null
./build/coons study data/boundaries data/triangles --out out/study
