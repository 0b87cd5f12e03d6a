#!/usr/bin/env python3
"""A distributed solve equals the one-rank solve: `mpirun -np K coons solve B --solver S` prints one
report (rank 0 alone), and its net agrees with that of `coons solve B --solver S` to 1e-10 relative.

usage: mpi_solve_check.py COONS MPIRUN RANKS SOLVER ALPHA DEGREE
The boundary (a wavy, non-planar frame of the given degree) is written to a temporary directory."""
import json
import math
import os
import subprocess
import sys
import tempfile


def boundary(n):
    def point(u, v):
        return [u, v, 0.3 * math.sin(3 * u + 1) * math.cos(2 * v) + 0.2 * u * v]

    t = [k / n for k in range(n + 1)]
    return {"name": "wavy", "degree": [n, n],
            "bottom": [point(s, 0) for s in t], "top": [point(s, 1) for s in t],
            "left": [point(0, s) for s in t], "right": [point(1, s) for s in t]}


def flat(x):
    if isinstance(x, list):
        for y in x:
            yield from flat(y)
    else:
        yield x


def main():
    coons, mpirun, ranks, solver, alpha, degree = sys.argv[1:7]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "wavy.json")
        with open(path, "w") as f:
            json.dump(boundary(int(degree)), f)
        args = ["solve", path, "--solver", solver, "--alpha", alpha]
        one = subprocess.run([coons] + args, capture_output=True, text=True, env=env)
        many = subprocess.run([mpirun, "--allow-run-as-root", "--oversubscribe", "-np", ranks, coons] + args,
                              capture_output=True, text=True, env=env)
    for name, run in (("1 rank", one), (ranks + " ranks", many)):
        if run.returncode != 0:
            sys.exit(f"{name}: exit {run.returncode}\nstdout: {run.stdout}\nstderr: {run.stderr}")
    if many.stdout.count('"net"') != 1:  # rank 0 alone prints
        sys.exit(f"{ranks} ranks printed {many.stdout.count(chr(34) + 'net' + chr(34))} reports:\n{many.stdout[:2000]}")
    a, b = json.loads(one.stdout), json.loads(many.stdout)
    for report in (a, b):
        if report["solver"]["status"] != "success":
            sys.exit(f"solver did not succeed: {report['solver']}")
    x, y = list(flat(a["net"])), list(flat(b["net"]))
    scale = max(abs(v) for v in x)
    difference = max(abs(p - q) for p, q in zip(x, y)) / scale
    print(f"{solver}, alpha {alpha}, degree {degree}: {ranks} ranks vs 1: relative difference {difference:.3g}; "
          f"iterations {a['solver']['iterations']} and {b['solver']['iterations']}")
    if len(x) != len(y) or not difference <= 1e-10:
        sys.exit("the nets differ by more than 1e-10 relative")


if __name__ == "__main__":
    main()
