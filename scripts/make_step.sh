#!/usr/bin/env bash
# Makes the sample STEP files of data/cad/ with OpenCASCADE (no download): the program
# coons_make_step (tests/cad/make_step_sample.cpp, built when OpenCASCADE is found) writes
#   data/cad/bspline_patch.step  one face: the Greville Coons surface of a B-spline boundary with
#                                non-uniform knots (degrees 3 and 2; tests/cad/cad_fixtures.cpp);
#   data/cad/four_edges.step     that boundary's four curves as free edges, shuffled, two reversed.
# The header time stamp is fixed, so the files are reproducible byte for byte.
#   scripts/make_step.sh           (re)write data/cad/
#   scripts/make_step.sh --check   write to a temporary folder and compare with data/cad/ (ctest)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${COONS_BUILD_DIR:-build}
if [ "${1:-}" != "--check" ]; then
  cmake --build "$build" -j2 --target coons_make_step
fi
[ -x "$build/coons_make_step" ] || { echo "error: make_step: $build/coons_make_step not built (needs OpenCASCADE: apt-get install libocct-data-exchange-dev libocct-modeling-algorithms-dev)" >&2; exit 1; }
if [ "${1:-}" = "--check" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  "$build/coons_make_step" "$tmp" >/dev/null
  for f in bspline_patch.step four_edges.step; do
    cmp "$tmp/$f" "data/cad/$f" || { echo "error: data/cad/$f differs from what scripts/make_step.sh makes" >&2; exit 1; }
  done
  echo "data/cad/*.step are what scripts/make_step.sh makes"
else
  mkdir -p data/cad
  "$build/coons_make_step" data/cad
fi
