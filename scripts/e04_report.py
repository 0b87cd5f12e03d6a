#!/usr/bin/env python3
"""Experiment E04's README from bench_solvers' BM_Hard JSON: tables and computed conclusions.

Usage: e04_report.py BENCH.json EXPERIMENT_DIR   (writes EXPERIMENT_DIR/README.md: question.md,
then the tables and the conclusions of this run; standard library only)
"""
import json
import os
import re
import sys
from collections import defaultdict


def seconds(b):
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    return b["real_time"] * unit


def status_of(b):
    label = b.get("label", "")
    return label.split("status=")[-1] if "status=" in label else ("success" if b.get("ok", 1) else "failure")


def main():
    path, folder = sys.argv[1], sys.argv[2]
    doc = json.load(open(path))
    memory, hard = {}, defaultdict(dict)  # (problem, backend) -> N -> (seconds, bench)
    for b in doc["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue
        n = int(b.get("N", 0))
        if b["name"].startswith("BM_MemoryPass/"):
            memory[n] = seconds(b)
        elif m := re.match(r"BM_Hard/([^/]+)/([^/]+)/N:", b["name"]):
            hard[(m.group(1), m.group(2))][n] = (seconds(b), b)
    sizes = sorted({n for per_n in hard.values() for n in per_n if n in memory})
    problems = list(dict.fromkeys(p for p, _ in hard))
    lines = [f"**Result** ({doc['context'].get('date', '')[:10]}, {doc['context'].get('num_cpus', '?')} CPUs, "
             "one run; wall-clock time of one fresh solve as a multiple of the memory pass at the same N;",
             "`it` iterations; ✗ the status when not `success`):", ""]
    winners = {}
    for problem in problems:
        lines += [f"### {problem}", "", "| backend | " + " | ".join(f"N={n}" for n in sizes) + " |",
                  "|" + "---|" * (len(sizes) + 1)]
        for (p, backend), per_n in hard.items():
            if p != problem:
                continue
            cells = []
            for n in sizes:
                if n not in per_n:
                    cells.append("–")
                    continue
                t, b = per_n[n]
                st = status_of(b)
                if st == "success":
                    it = int(b.get("iterations", 1))
                    cells.append(f"{t / memory[n]:.1f}×" + (f", {it} it" if it > 1 else "") +
                                 f", res {b.get('residual', 0):.0e}")
                    best = winners.get((problem, n))
                    if best is None or t < best[1]:
                        winners[(problem, n)] = (backend, t)
                else:
                    cells.append(f"✗ {st}")
            lines.append(f"| {backend} | " + " | ".join(cells) + " |")
        lines.append("")
    lines += ["## Conclusions (computed from the tables above)", ""]
    for problem in problems:
        parts = []
        for n in sizes:
            if (problem, n) not in winners:
                continue
            backend, t = winners[(problem, n)]
            others = sorted((per_n[n][0], b) for (p, b), per_n in hard.items()
                            if p == problem and b != backend and n in per_n and status_of(per_n[n][1]) == "success")
            runner = f"; next {others[0][1]} {others[0][0] / t:.1f}× slower" if others else ""
            parts.append(f"N = {n}: `{backend}` ({t / memory[n]:.1f}× mem{runner})")
        lines.append(f"- **{problem}** — fastest: " + "; ".join(parts) + ".")
    declined = defaultdict(list)
    for (p, backend), per_n in hard.items():
        if any(status_of(b) == "not_applicable" for _, b in per_n.values()):
            declined[backend].append(p)
    for backend, ps in sorted(declined.items()):
        lines.append(f"- `{backend}` declined (not_applicable): {', '.join(ps)}.")
    stopped = sorted({(b, p) for (p, b), per_n in hard.items()
                      for _, bb in per_n.values() if status_of(bb) not in ("success", "not_applicable")})
    for backend, p in stopped:
        lines.append(f"- `{backend}` did not finish on {p} at some N (status in the table).")
    question = open(os.path.join(folder, "question.md")).read()
    with open(os.path.join(folder, "README.md"), "w") as out:
        out.write(question + "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
