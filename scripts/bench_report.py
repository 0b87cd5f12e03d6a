#!/usr/bin/env python3
"""Turns bench_solvers' JSON into a Markdown table, log-log plots and scaling exponents.

Every time is divided by the memory pass (BM_MemoryPass) at the same N from the same run.
Usage: bench_report.py BENCH.json OUT_DIR    (standard library only; gnuplot draws the PNGs)
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
from collections import defaultdict


def seconds(b):
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    return b["real_time"] * unit


def fit_exponent(points):
    """Least-squares slope of log(time) against log(unknowns)."""
    if len(points) < 2:
        return None
    xs = [math.log(u) for u, _ in points]
    ys = [math.log(t) for _, t in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else None


def search_cost(label, seconds, one_solve):
    """A search with its optimal net, in solves: the sine-basis search adds the net's one solve."""
    return (seconds + (one_solve if "sine basis" in label else 0)) / one_solve


def summary(doc, memory, solve, exponents, sizes):
    """Every backend at the largest N ≤ 1023 it reached, one row each, fastest first at α = −0.1:
    the block bench.sh copies into docs/solvers.md."""
    alphas = sorted({a for _, a in solve})
    backends = sorted({b for b, _ in solve})

    def reached(backend):
        return max((n for (b, _), per_n in solve.items() if b == backend for n in per_n if n <= 1023), default=0)

    def cell(backend, alpha, n):
        hit = solve.get((backend, alpha), {}).get(n)
        if not hit:
            return "–"
        t, b = hit
        text = f"{t:.3g} s ({t / memory[n]:.1f}×)" if n in memory else f"{t:.3g} s"
        if b.get("iterations", 1) > 1:
            text += f", {int(b['iterations'])} it"
        return text + ("" if b.get("ok", 1) else " ✗ " + b.get("label", "").split("status=")[-1])

    def key(backend):
        n = reached(backend)
        hit = solve.get((backend, -0.1), {}).get(n)
        return (-n, hit[0] if hit else float("inf"))

    date = doc["context"].get("date", "")[:10]
    lines = [f"Every backend at the largest N (at most 1023) it ran at, from E03's run of {date} "
             f"({doc['context'].get('num_cpus', '?')} CPUs; wall-clock seconds of one fresh solve, 3 right-hand sides, "
             "and in brackets the multiple of the memory pass of the same run; `it` iterations; ✗ the status when "
             "not `success`; the exponent is the growth of the time with the unknowns at α = −1/4, or at the "
             "first α the backend ran). Sorted by N, then by the time at α = −0.1.", "",
             "| backend | N | " + " | ".join(f"α = {a:g}" for a in alphas) + " | exponent |",
             "|---|---|" + "---|" * len(alphas) + "---|"]
    for backend in sorted(backends, key=key):
        n = reached(backend)
        if not n:
            continue
        e = next((exponents.get((backend, a)) for a in alphas if exponents.get((backend, a)) is not None), None)
        lines.append(f"| `{backend}` | {n} | " + " | ".join(cell(backend, a, n) for a in alphas) +
                     f" | {e:.2f} |" if e is not None else f"| `{backend}` | {n} | " +
                     " | ".join(cell(backend, a, n) for a in alphas) + " | – |")
    mem = ", ".join(f"N = {n}: {memory[n] * 1e3:.3f} ms" for n in sizes if n in memory and n <= 1023)
    return "\n".join(lines) + f"\n\nMemory pass of that run: {mem}.\n"


def main():
    path, out = sys.argv[1], sys.argv[2]
    doc = json.load(open(path))
    runs = [b for b in doc["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
    memory = {}            # N -> seconds
    simple = defaultdict(dict)   # name -> N -> seconds (closed form, assembly, refill)
    solve = defaultdict(dict)    # (backend, alpha) -> N -> (seconds, bench)
    refactor = defaultdict(dict)
    sweep = defaultdict(dict)    # backend -> N -> seconds
    ordering = defaultdict(dict)  # (ordering) -> N -> seconds
    search = defaultdict(dict)    # backend -> N -> (seconds, bench)
    stencil5 = defaultdict(dict)  # (problem, backend) -> N -> (seconds, bench)
    for b in runs:
        name = b["name"]
        n = int(b.get("N", 0))
        t = seconds(b)
        if name.startswith("BM_MemoryPass/"):
            memory[n] = t
        elif m := re.match(r"BM_(ClosedFormCoons|Assemble|RefillValues)/", name):
            simple[m.group(1)][n] = t
        elif m := re.match(r"BM_(Solve|Refactorize)/([^/]+)/N:\d+/alpha:([-0-9.]+)(?:/threads:(\d+))?", name):
            backend = m.group(2) + (f" ({m.group(4)} threads)" if m.group(4) else "")
            key = (backend, float(m.group(3)))
            (solve if m.group(1) == "Solve" else refactor)[key][n] = (t, b)
        elif m := re.match(r"BM_AlphaSweep/([^/]+)/", name):
            sweep[m.group(1)][n] = t
        elif m := re.match(r"BM_SearchAlpha/([^/]+)/", name):
            search[m.group(1) + " (solve per evaluation)"][n] = (t, b)
        elif m := re.match(r"BM_SearchAlphaSpectral/([^/]+)/", name):
            search[m.group(1) + " (sine basis)"][n] = (t, b)
        elif m := re.match(r"BM_CholmodOrdering/([^/]+)/", name):
            ordering[m.group(1)][n] = t
        elif m := re.match(r"BM_Stencil5/([^/]+)/([^/]+)/N:\d+(?:/threads:(\d+))?", name):
            backend = m.group(2) + (f" ({m.group(3)} threads)" if m.group(3) else "")
            stencil5[(m.group(1), backend)][n] = (t, b)

    lines = [f"# Solver scaling: {doc['context'].get('date', '')}, {doc['context'].get('num_cpus', '?')} CPUs",
             "",
             "Times are real (wall-clock) seconds of one fresh solve (analyze + factorize + solve, 3 right-hand",
             "sides); `× mem` divides by the memory pass (read 3 RHS columns, write 3 solution columns) at the",
             "same N, measured in the same run.",
             ""]
    sizes = sorted(memory)
    lines.append("| N | unknowns | memory pass [ms] | closed-form Coons [× mem] | assembly [× mem] | value refill [× mem] |")
    lines.append("|---|---|---|---|---|---|")
    for n in sizes:
        def ratio(name):
            return f"{simple[name][n] / memory[n]:.2f}" if n in simple[name] else "–"
        lines.append(f"| {n} | {n * n} | {memory[n] * 1e3:.3f} | {ratio('ClosedFormCoons')} | {ratio('Assemble')} | {ratio('RefillValues')} |")
    lines.append("")

    alphas = sorted({a for _, a in solve})
    exponents = {}
    for alpha in alphas:
        lines.append(f"## α = {alpha}")
        lines.append("")
        header = "| backend | " + " | ".join(f"N={n}" for n in sizes) + " | exponent | notes |"
        lines.append(header)
        lines.append("|" + "---|" * (len(sizes) + 3))
        for (backend, a), per_n in sorted(solve.items()):
            if a != alpha:
                continue
            cells, notes = [], set()
            points = []
            for n in sizes:
                if n in per_n:
                    t, b = per_n[n]
                    cell = f"{t:.3g} s ({t / memory[n]:.1f}×)"
                    if not b.get("ok", 1):
                        cell += " ✗"
                        notes.add(b.get("label", "").split("status=")[-1])
                    else:
                        points.append((n * n, t))
                    if b.get("iterations", 1) > 1:
                        cell += f" {int(b['iterations'])} it"
                    cells.append(cell)
                else:
                    cells.append("–")
                label = per_n.get(n, (0, {}))[1].get("label", "")
                if "ordering=" in label:
                    notes.add(label.split("ordering=")[1].split()[0])
            big = [p for p in points if p[0] >= 127 * 127] or points
            e = fit_exponent(big)
            exponents[(backend, alpha)] = e
            lines.append(f"| {backend} | " + " | ".join(cells) + f" | {e:.2f} |" if e is not None else f"| {backend} | " + " | ".join(cells) + " | – |")
            lines[-1] += " " + ", ".join(sorted(x for x in notes if x)) + " |"
        lines.append("")

    if refactor:
        lines.append("## Analysis reused (factorize + solve per α) vs a fresh solve, largest N measured")
        lines.append("")
        lines.append("| backend | α | N | fresh [s] | refactorize [s] | ratio |")
        lines.append("|---|---|---|---|---|---|")
        for (backend, alpha), per_n in sorted(refactor.items()):
            n = max(per_n)
            if n in solve.get((backend, alpha), {}):
                fresh = solve[(backend, alpha)][n][0]
                lines.append(f"| {backend} | {alpha} | {n} | {fresh:.3g} | {per_n[n][0]:.3g} | {per_n[n][0] / fresh:.2f} |")
        lines.append("")

    if sweep:
        lines.append("## α sweep: 101 values of α through the sweep API, as a multiple of one solve at α = −0.1")
        lines.append("")
        lines.append("| backend | N | sweep [s] | one solve [s] | sweep / one solve |")
        lines.append("|---|---|---|---|---|")
        for backend, per_n in sorted(sweep.items()):
            for n, t in sorted(per_n.items()):
                one = solve.get((backend, -0.1), {}).get(n)
                if one:
                    lines.append(f"| {backend} | {n} | {t:.3g} | {one[0]:.3g} | {t / one[0]:.1f} |")
        lines.append("")

    if search:
        lines.append("## α search (scan + Ceres, discrete thin-plate objective) as a multiple of one solve at α = −0.1")
        lines.append("")
        lines.append("The sine-basis search ends with α*; its optimal net is one more solve, which the last column adds")
        lines.append("at the measured cost of one solve. The solve-per-evaluation search already holds that net.")
        lines.append("")
        lines.append("| backend | N | search [s] | evaluations | solves | one solve [s] | (search + net) / one solve |")
        lines.append("|---|---|---|---|---|---|---|")
        for backend, per_n in sorted(search.items()):
            for n, (t, b) in sorted(per_n.items()):
                one = solve.get((backend.split()[0], -0.1), {}).get(n)
                ratio = f"{search_cost(backend, t, one[0]):.1f}" if one else "–"
                lines.append(f"| {backend} | {n} | {t:.3g} | {int(b.get('evaluations', 0))} | {int(b.get('solves', 0))} | "
                             f"{one[0]:.3g} | {ratio} |" if one else f"| {backend} | {n} | {t:.3g} | – | – | – | – |")
        lines.append("")

    if stencil5:
        lines.append("## 5×5 masks (two data rings): fresh solve as a multiple of the memory pass")
        lines.append("")
        lines.append("c1-coons = C, biharmonic = T, c1-family-0.5 = (C + T)/2 on the full N×N rectangle;")
        lines.append("hole-0.5 = the same with a centred square of side N/4 fixed. `it`: iterations (fast5: of")
        lines.append("the capacitance CG; pcg-fast: of the outer CG); `res`: true relative residual.")
        lines.append("")
        n5 = sorted({n for per_n in stencil5.values() for n in per_n})
        lines.append("| problem | backend | " + " | ".join(f"N={n}" for n in n5) + " |")
        lines.append("|" + "---|" * (len(n5) + 2))
        for (problem, backend), per_n in sorted(stencil5.items()):
            cells = []
            for n in n5:
                if n not in per_n or n not in memory:
                    cells.append("–")
                    continue
                t, b = per_n[n]
                cell = f"{t:.3g} s ({t / memory[n]:.1f}×), {int(b.get('iterations', 1))} it, res {b.get('residual', 0):.1e}"
                if not b.get("ok", 1):
                    cell += " ✗"
                cells.append(cell)
            lines.append(f"| {problem} | {backend} | " + " | ".join(cells) + " |")
        lines.append("")

    if ordering:
        lines.append("## CHOLMOD supernodal by ordering (α = −0.25)")
        lines.append("")
        lines.append("| ordering | " + " | ".join(f"N={n}" for n in sizes) + " |")
        lines.append("|" + "---|" * (len(sizes) + 1))
        for name, per_n in sorted(ordering.items()):
            lines.append(f"| {name} | " + " | ".join(f"{per_n[n]:.3g} s" if n in per_n else "–" for n in sizes) + " |")
        lines.append("")

    # Targets of the solver issue, at the largest N ≥ 1023 this run measured (computed, never typed in).
    big = [n for n in sizes if n >= 1023]
    if big:
        n = 1023 if 1023 in big else big[0]
        mem = memory[n]
        lines.append(f"## Targets at N = {n} (memory pass {mem * 1e3:.3f} ms in this run)")
        lines.append("")
        lines.append("| target | achieved | goal | met |")
        lines.append("|---|---|---|---|")

        def row(what, value, goal, unit="× mem"):
            if value is None:
                lines.append(f"| {what} | not measured | ≤ {goal} {unit} | – |")
                return
            ok = value <= goal
            miss = "" if ok else f" (missed by {value / goal:.2f}×)"
            lines.append(f"| {what} | {value:.2f} {unit} | ≤ {goal} {unit} | {'yes' if ok else 'no' + miss} |")

        def ratio(backend, alpha):
            hit = solve.get((backend, alpha), {}).get(n)
            return hit[0] / mem if hit and hit[1].get("ok", 1) else None

        fast_alphas = [a for (b, a) in solve if b == "fast" and n in solve[(b, a)] and -0.25 <= a <= 0.25]
        worst_fast = max((ratio("fast", a) for a in fast_alphas if ratio("fast", a) is not None), default=None)
        row("`fast`, worst α in [−1/4, 1/4]", worst_fast, 5)
        row("`fast`, α = −1/4", ratio("fast", -0.25), 3)
        worst_dst = max((ratio("dst", a) for (b, a) in solve if b == "dst" and ratio("dst", a) is not None), default=None)
        row("`dst`, worst α", worst_dst, 15)
        row("closed-form Coons net", simple["ClosedFormCoons"][n] / mem if n in simple["ClosedFormCoons"] else None, 1.5)
        auto_worst = None
        for (b, a), per_n in solve.items():
            if b != "auto" or n not in per_n:
                continue
            fastest = min(t for (bb, aa), pn in solve.items() if aa == a and bb != "auto" and "threads)" not in bb and n in pn and pn[n][1].get("ok", 1)
                          for t in [pn[n][0]])
            r = per_n[n][0] / fastest
            auto_worst = r if auto_worst is None else max(auto_worst, r)
        row("`auto` / fastest backend", auto_worst, 1.1, "×")
        one = solve.get(("fast", -0.1), {}).get(n)
        row("α sweep of 101 values / one `fast` solve", sweep["fast"][n] / one[0] if one and n in sweep.get("fast", {}) else None, 60, "×")
        for label in sorted(search):
            sr = search[label].get(n)
            row(f"α search with its net, {label.split(' ', 1)[1][1:-1]}, / one `fast` solve",
                search_cost(label, sr[0], one[0]) if sr and one else None, 10, "×")
        def ratio5(problem, backend):
            hit = stencil5.get((problem, backend), {}).get(n)
            return hit[0] / mem if hit and hit[1].get("ok", 1) else None

        if stencil5:
            row("c1-coons via `separable-banded`", ratio5("c1-coons", "separable-banded"), 3)
            row("biharmonic via `fast5`", ratio5("biharmonic", "fast5"), 10)
            row("c1-family w = 0.5 via `fast5`", ratio5("c1-family-0.5", "fast5"), 10)
            row("c1-coons via `separable-banded`, 2 threads", ratio5("c1-coons", "separable-banded (2 threads)"), 3)
            row("biharmonic via `fast5`, 2 threads", ratio5("biharmonic", "fast5 (2 threads)"), 10)
            row("c1-family w = 0.5 via `fast5`, 2 threads", ratio5("c1-family-0.5", "fast5 (2 threads)"), 10)
        chol = ordering and {name: per_n[n] for name, per_n in ordering.items() if n in per_n}
        if chol and ("cholmod", -0.25) in solve and n in solve[("cholmod", -0.25)]:
            best = min(chol.values())
            row("`cholmod` / its best ordering (α = −1/4)", solve[("cholmod", -0.25)][n][0] / best, 1.0, "×")
        lines.append("")

    table = "\n".join(lines) + "\n"
    open(os.path.join(out, "table.md"), "w").write(table)
    open(os.path.join(out, "summary.md"), "w").write(summary(doc, memory, solve, exponents, sizes))
    print(table)

    if shutil.which("gnuplot") and not os.environ.get("COONS_NO_PLOTS"):
        for alpha in alphas:
            series = [(backend, per_n) for (backend, a), per_n in sorted(solve.items()) if a == alpha]
            data_files = []
            for backend, per_n in series:
                f = os.path.join(out, f"data_{backend}_{alpha}.dat")
                with open(f, "w") as fh:
                    for n in sorted(per_n):
                        t, b = per_n[n]
                        if b.get("ok", 1):
                            fh.write(f"{n * n} {t}\n")
                data_files.append((backend, f))
            mem = os.path.join(out, "data_memory.dat")
            with open(mem, "w") as fh:
                for n in sizes:
                    fh.write(f"{n * n} {memory[n]}\n")
            png = os.path.join(out, f"scaling_alpha{alpha}.png")
            plots = [f"'{mem}' using 1:2 with lines lw 3 lc rgb 'black' title 'memory pass (floor)'"]
            plots += [f"'{f}' using 1:2 with linespoints title '{backend}'" for backend, f in data_files]
            script = (f"set terminal pngcairo size 1000,700; set output '{png}'; set logscale xy; "
                      f"set xlabel 'unknowns'; set ylabel 'seconds (one solve, 3 RHS)'; set key outside right; "
                      f"set grid; set title 'Mask systems, alpha = {alpha}'; plot " + ", ".join(plots))
            subprocess.run(["gnuplot", "-e", script], check=True)
            for _, f in data_files:
                os.remove(f)
            os.remove(mem)


if __name__ == "__main__":
    main()
