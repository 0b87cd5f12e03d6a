#!/usr/bin/env python3
"""End-to-end `coons solve` of a large net: wall seconds, CPU seconds, maximum resident memory and
the report's per-phase seconds (its "timing" block), at degree N (default 1000: a 1001x1001 net).

    experiments/benchmarks/bench_solve_e2e.py [--coons build/coons] [--degree 1000] [--solver fast] [--threads 1] [--json OUT]

The boundary is the dome of data/boundaries refitted to degree N (`coons refit`); the report goes
to a temporary file. Needs /usr/bin/time (GNU time) for the memory figure. --json also writes the
figures as one JSON object (scripts/bench_mg.sh passes it to scripts/mg_report.py, which checks
issue 14's end-to-end target).
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import tempfile


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--coons", default=os.path.join(root, "build", "coons"))
    p.add_argument("--degree", type=int, default=1000)
    p.add_argument("--solver", default="fast")
    p.add_argument("--threads", type=int, default=1, help="coons solve --threads (the solver and the energies)")
    p.add_argument("--json", help="also write the figures here as one JSON object")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        boundary = os.path.join(tmp, "dome.json")
        subprocess.run([a.coons, "refit", os.path.join(root, "data", "boundaries", "dome.json"), "--degree",
                        str(a.degree), str(a.degree), "--out", boundary], check=True, stdout=subprocess.DEVNULL)
        out = os.path.join(tmp, "report.json")
        # --threads only when asked for: coons refuses it with a backend that runs on one thread
        threads = ["--threads", str(a.threads)] if a.threads != 1 else []
        started = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
        load_at_start = list(os.getloadavg())  # before the solve, which would raise it
        with open(out, "w") as f:
            r = subprocess.run(["/usr/bin/time", "-v", a.coons, "solve", boundary, "--solver", a.solver] + threads,
                               stdout=f, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            sys.exit(f"coons solve failed ({r.returncode}): {r.stderr}")
        field = lambda name: re.search(re.escape(name) + r":\s*(\S+)", r.stderr).group(1)
        wall = field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":")
        wall_s = float(wall[-1]) + 60 * float(wall[-2]) + (3600 * float(wall[-3]) if len(wall) > 2 else 0)
        cpu = float(field("User time (seconds)")) + float(field("System time (seconds)"))
        rss_mb = int(field("Maximum resident set size (kbytes)")) / 1024
        size_mb = os.path.getsize(out) / 2**20
        with open(out) as f:
            report = json.load(f)
    print(f"coons solve, degree {a.degree} ({a.degree + 1}x{a.degree + 1} net), --solver {a.solver} --threads {a.threads}")
    print(f"  wall {wall_s:.2f} s, CPU {cpu:.2f} s, max RSS {rss_mb:.0f} MB, report {size_mb:.0f} MB")
    for phase, seconds in report["timing"].items():
        print(f"  {phase:8s} {seconds:8.3f} s")
    print(f"  e3_energy {report['metrics']['e3_energy']!r}, thin_plate_energy {report['metrics']['thin_plate_energy']!r}")
    if a.json:
        figures = {"date": started, "load_avg": load_at_start, "num_cpus": os.cpu_count(), "degree": a.degree,
                   "solver": a.solver, "threads": a.threads, "wall_seconds": wall_s, "cpu_seconds": cpu, "max_rss_mb": rss_mb,
                   "report_mb": size_mb, "timing": report["timing"]}
        with open(a.json, "w") as f:
            json.dump(figures, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
