#!/usr/bin/env bash
# Installs the Debian 12 packages coons needs, when any is missing. Idempotent: prints nothing
# and touches nothing when everything is there. Called by scripts/main.sh and scripts/test.sh.
set -euo pipefail

packages=(
  g++ cmake make                # compiler and build
  libeigen3-dev                 # dense/sparse linear algebra, the solver interface's matrices
  libsuitesparse-dev            # CHOLMOD and UMFPACK backends
  libopenblas-dev               # fast BLAS for CHOLMOD's supernodal factorisation
  libmetis-dev                  # nested-dissection orderings
  libceres-dev                  # the alpha search (optimiser)
  libbenchmark-dev              # the solver benchmarks
  catch2                        # the test suite (v2.13)
  libfftw3-dev                  # sine-transform solvers
  libhypre-dev                  # optional hypre backends: hypre-amg (BoomerAMG), hypre-pfmg, hypre-smg
  openmpi-bin libopenmpi-dev    # MPI for hypre and distributed solves (mpirun -np K coons solve ...)
  libocct-data-exchange-dev libocct-modeling-algorithms-dev  # optional OpenCASCADE: import-step, export --step/--iges
  libcli11-dev                  # command-line parsing
  nlohmann-json3-dev            # JSON in and out
  libfmt-dev                    # formatting
  libmuparser-dev               # analytic curves written as expressions
  libboost-dev                  # Brent's minimiser, the independent check of the alpha search
  gnuplot-nox                   # PNG plots of reports and benchmarks
  python3                       # benchmark tables (scripts/bench_report.py, standard library only)
  python3-jsonschema            # the documentation checks: data files against docs/schema/ (scripts/check_docs.py)
  clang libclang-rt-14-dev      # libFuzzer and clang's sanitizer runtimes: scripts/fuzz.sh (run by .ci/run)
  libjs-three                   # three.js (r111), inlined into the pages of `coons view` (optional)
  chromium                      # the headless-browser test of `coons view` pages (optional)
  clang-format clang-tidy       # the style checks of .ci/run: scripts/format.sh --check, scripts/tidy.sh
  parallel time                 # sharded studies on one machine: scripts/study-parallel.sh (GNU parallel; /usr/bin/time -v for --time)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "error: setup: missing packages (${missing[*]}) and not root, no sudo" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
