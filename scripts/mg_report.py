#!/usr/bin/env python3
"""Tables of the multigrid iteration counts and of the 1- and 2-thread solves, from bench_solvers JSON.

    python3 scripts/mg_report.py --iterations A.json [B.json ...] [--threads T.json] [--e2e E.json ...]
                                 [--sizes S.json] [--docs docs/solvers.md]

--iterations: `bench_solvers --mg-iterations --benchmark_out=...` runs (several files are merged, e.g.
a run that was split by size); --threads: a BM_Solve run with the threaded backends
(`--large --backends=fast,dst,mg,fast5,separable-banded`, scripts/bench_mg.sh); --e2e: the JSON of
experiments/benchmarks/bench_solve_e2e.py (one `coons solve` of a 1001x1001 net); --sizes: a BM_Solve run
of fast and dst at N = 1000, 1023, 1024, 1030 (one thread). Prints Markdown; with --docs it replaces the text between the markers
<!-- mg-report:begin --> and <!-- mg-report:end --> of that file.
"""
import argparse
import json
import re
import sys

BEGIN, END = "<!-- mg-report:begin -->", "<!-- mg-report:end -->"


def missed_by(ratio):
    """How far a measurement above its goal is: a percentage when close (1.04 reads "4 %", not
    "1.0×"), else a factor."""
    return f"missed by {100 * (ratio - 1):.0f} %" if ratio < 1.5 else f"missed by {ratio:.1f}×"


def load(path):
    """A bench_solvers JSON run; of a run with repetitions, the medians only, named as single runs."""
    with open(path) as f:
        data = json.load(f)
    medians = [b for b in data.get("benchmarks", []) if b.get("aggregate_name") == "median"]
    if medians:
        for b in medians:
            b["name"] = b["run_name"]
        data["benchmarks"] = medians
        data["repetitions"] = max(int(b.get("repetitions", 1)) for b in medians)
    return data


def seconds_of(b, key="real_time"):
    """A benchmark entry's time in seconds."""
    return b[key] * {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]


def memory_passes(data):
    """N → seconds of BM_MemoryPass/N in a bench_solvers run."""
    out = {}
    for b in data["benchmarks"]:
        m = re.match(r"BM_MemoryPass/N:(\d+)", b["name"])
        if m:
            out[int(m.group(1))] = seconds_of(b)
    return out


def load_note(data):
    ctx = data.get("context", {})
    loads = ctx.get("load_avg", [])
    when = ctx.get("date", "?")
    text = f"run {when}, {ctx.get('num_cpus', '?')} cores"
    if loads:
        text += ", load average at the start " + ", ".join(f"{x:.1f}" for x in loads)
    if data.get("repetitions", 1) > 1:
        text += f"; each time the median of {data['repetitions']} repetitions"
    return text


def iteration_table(data):
    rows, sizes, counts = {}, set(), {}
    for b in data["benchmarks"]:
        m = re.match(r"BM_MgIterations/([^/]+)/([^/]+)/N:(\d+)", b["name"])
        if not m:
            continue
        problem, backend, n = m.group(1), m.group(2), int(m.group(3))
        problem = problem.replace("alpha:", "α = ").replace("-0.25", "−1/4").replace("-0.1", "−0.1")
        sizes.add(n)
        label = b.get("label", "")
        status = label.split("status=")[-1] if "status=" in label else "?"
        it = int(b.get("iterations", -1))
        res = b.get("residual", float("nan"))
        seconds = seconds_of(b)
        if status == "success":
            cell = f"{it} ({seconds:.1f} s)"
        elif status == "not_applicable":
            cell = "not_applicable"
        else:
            cell = f"{status}: {it} it., residual {res:.1e}"
        rows[(problem, backend)] = rows.get((problem, backend), {})
        rows[(problem, backend)][n] = cell
        counts.setdefault((problem, backend), {})[n] = (it, status)
    sizes = sorted(sizes)
    out = ["| problem | backend | " + " | ".join(f"N = {n}" for n in sizes) + " |",
           "|---|---|" + "---|" * len(sizes)]
    for (problem, backend), cells in rows.items():
        out.append(f"| {problem} | `{backend}` | " + " | ".join(cells.get(n, "–") for n in sizes) + " |")
    # Issue 14's iteration targets at the largest size of the run: `mg` ≤ 10 cycles at α = 0 and
    # −0.1, `mg-cg` ≤ 40 iterations at α = −1/4 and on c1-coons and the biharmonic.
    goals = [("α = 0.000", "mg", 10, "cycles"), ("α = −0.10", "mg", 10, "cycles"),
             ("α = −1/4", "mg-cg", 40, "iterations"), ("c1-coons", "mg-cg", 40, "iterations"),
             ("biharmonic", "mg-cg", 40, "iterations")]
    targets = []
    for problem, backend, goal, unit in goals:
        if not sizes or (problem, backend) not in counts or sizes[-1] not in counts[(problem, backend)]:
            continue
        n = sizes[-1]
        it, status = counts[(problem, backend)][n]
        verdict = ("met" if it <= goal else f"missed by {it - goal} {unit}") if status == "success" else status
        measured = f"{it} {unit if it != 1 else unit[:-1]}"
        targets.append(f"| `{backend}` on {problem}, N = {n} | {measured} ({status}) | ≤ {goal} | {verdict} |")
    if targets:
        out += ["", "Issue 14's iteration targets, same run (to relative residual 1e−10):", "",
                "| target | measured | goal | |", "|---|---|---|---|"] + targets
    return "\n".join(out)


def threads_table(data):
    memory, solves, cycles = memory_passes(data), {}, {}
    for b in data["benchmarks"]:
        t = seconds_of(b)
        cpu = seconds_of(b, "cpu_time")
        m = re.match(r"BM_Solve/([^/]+)/N:(\d+)/alpha:([^/]+)(/threads:(\d+))?", b["name"])
        if m:
            key = (m.group(1), int(m.group(2)), m.group(3))
            solves.setdefault(key, {})[int(m.group(5) or 1)] = (t, cpu, b.get("label", ""))
            cycles[(key, int(m.group(5) or 1))] = int(b.get("iterations", 0))
            continue
        m = re.match(r"BM_Stencil5/([^/]+)/([^/]+)/N:(\d+)(/threads:(\d+))?", b["name"])
        if m:  # the 5×5 set: the problem's name in the α column
            key = (m.group(2), int(m.group(3)), m.group(1))
            solves.setdefault(key, {})[int(m.group(5) or 1)] = (t, cpu, b.get("label", ""))
    out = ["| backend | N | α | 1 thread (wall) | 2 threads (wall) | speed-up | 1 thread / memory pass | 2 threads / memory pass |",
           "|---|---|---|---|---|---|---|---|"]
    for (backend, n, alpha), by in sorted(solves.items()):
        if 1 not in by or 2 not in by:
            continue
        one, two = by[1][0], by[2][0]
        mem = memory.get(n)
        ratio = (lambda x: f"{x / mem:.0f}×") if mem else (lambda x: "–")
        out.append(f"| `{backend}` | {n} | {alpha} | {one * 1e3:.1f} ms | {two * 1e3:.1f} ms | {one / two:.2f} | "
                   f"{ratio(one)} | {ratio(two)} |")
    mem_note = ", ".join(f"N = {n}: {t * 1e3:.2f} ms" for n, t in sorted(memory.items()))
    text = "\n".join(out) + f"\n\nMemory pass of the same run: {mem_note}."
    # Every speed target of issues 11 and 14, from the same run, at one and at two threads.
    sweeps = {}
    for b in data["benchmarks"]:
        m = re.match(r"BM_AlphaSweep(Threads)?/fast/N:(\d+)", b["name"])
        if m:
            sweeps[(int(m.group(2)), 2 if m.group(1) else 1)] = \
                seconds_of(b)
    goals = {("fast", "-0.1"): (4, "`fast` at α = −0.1"), ("dst", "-0.1"): (15, "`dst` at α = −0.1"),
             ("mg", "0.0"): (20, "`mg` at α = 0"), ("mg", "-0.1"): (20, "`mg` at α = −0.1"),
             ("separable-banded", "c1-coons"): (3, "`separable-banded` on c1-coons"),
             ("fast5", "biharmonic"): (10, "`fast5` on biharmonic"),
             ("fast5", "c1-family-0.5"): (10, "`fast5` on the c1 family, w = 0.5")}

    def same_alpha(alpha, goal_alpha):  # an α column, or a 5×5 problem's name
        try:
            return float(alpha) == float(goal_alpha)
        except ValueError:
            return alpha == goal_alpha

    def verdict(r, goal):
        return "met" if r <= goal else missed_by(r / goal)

    rows = []
    for (backend, n, alpha), by in sorted(solves.items()):
        goal = next((g for (gb, ga), g in goals.items() if gb == backend and same_alpha(alpha, ga)), None)
        if goal and n in memory:
            for k in sorted(by):
                r = by[k][0] / memory[n]
                rows.append(f"| {goal[1]}, N = {n} / memory pass | {k} | {r:.1f}× | ≤ {goal[0]}× | {verdict(r, goal[0])} |")
        if backend == "fast" and same_alpha(alpha, "-0.1"):
            for k in sorted(by):
                if (n, k) in sweeps:
                    r = sweeps[(n, k)] / by[k][0]
                    rows.append(f"| 101-value α sweep / one `fast` solve, N = {n} | {k} | {r:.0f}× | ≤ 60× | {verdict(r, 60)} |")
    if rows:
        text += ("\n\nThe speed targets of issues 11 and 14, same run (wall-clock; threads as in the table above):\n\n"
                 "| target | threads | measured | goal | |\n|---|---|---|---|---|\n" + "\n".join(rows))
    # The transform solvers' floor: the rows' inverse sine transform and the write of the result
    # alone (BM_SineRows), beside a `fast` solve at α = −0.1 and its sweep's members.
    floors = {}
    for b in data["benchmarks"]:
        m = re.match(r"BM_SineRows/N:(\d+)(/threads:(\d+))?", b["name"])
        if m:
            floors[(int(m.group(1)), int(m.group(3) or 1))] = seconds_of(b)
    floor_notes = []
    for (n, k), t in sorted(floors.items()):
        if n not in memory:
            continue
        note = f"{k} thread{'s' if k > 1 else ''}: {t * 1e3:.1f} ms, {t / memory[n]:.1f}× the memory pass"
        fast_key = next((key for key in solves if key[0] == "fast" and key[1] == n and same_alpha(key[2], "-0.1")),
                        None)
        solve = solves[fast_key].get(k) if fast_key else None
        if solve:
            note += f", {t / solve[0]:.2f} of a `fast` solve at α = −0.1"
            # the `fast` goal in memory passes, against the floor its solve cannot go below
            fast_goal, floor_passes = goals[("fast", "-0.1")][0], t / memory[n]
            if floor_passes >= fast_goal:
                note += f", which alone exceeds the `fast` goal (≤ {fast_goal}×)"
            else:
                note += (f", which leaves {fast_goal - floor_passes:.1f}× of the `fast` goal (≤ {fast_goal}×) for its "
                         f"eliminations and set-up (they take {(solve[0] - t) / memory[n]:.1f}× now)")
            if (n, k) in sweeps and (n, 1) in floors:
                # A sweep on k threads runs its members side by side on k one-thread workers, so a
                # member's floor in wall time is the one-thread floor over k (not the k-thread one).
                member_floor = floors[(n, 1)] / k
                note += (f"; a member of its 101-value sweep has the floor {member_floor * 1e3:.2f} ms "
                         f"({'this one' if k == 1 else f'the one-thread floor over {k} workers'}), "
                         f"{member_floor / (sweeps[(n, k)] / 101):.2f} of the member's time")
                # the sweep goal allows 60/101 of a solve per member; a member that writes its net
                # through the rows' transform costs at least the floor, and the rest is its eliminations
                allowed, floor = 60 / 101, member_floor / solve[0]
                member = sweeps[(n, k)] / 101 / solve[0]
                note += (f"; the sweep goal (≤ 60× one solve) allows a member {allowed:.2f} of a solve, against "
                         f"{floor:.2f} for that floor")
                if floor >= allowed:
                    note += ", which alone exceeds it"
                else:
                    note += (f", which leaves {allowed - floor:.2f} of a solve for its eliminations "
                             f"(they take {member - floor:.2f} now)")
        floor_notes.append(f"N = {n}, {note}")
    if floor_notes:
        text += ("\n\nThe floor of a solve that transforms rows, same run (`BM_SineRows`: the inverse sine transform of "
                 "every row of the three columns and the write of the result, nothing else; `fast` does that and its "
                 "eliminations, and so does each member of its sweep): " + "; ".join(floor_notes) + ".")
    # fast5's floor on mask data: one banded sweep of the grid (BM_Fast5Sweep) and one row transform
    # (BM_SineRows), beside a fast5 solve of the biharmonic and its goal. (Since the twisted sweep
    # the solve does both in one pass, and can take less than the two.)
    sweeps5 = {}
    for b in data["benchmarks"]:
        m = re.match(r"BM_Fast5Sweep/N:(\d+)(/threads:(\d+))?", b["name"])
        if m:
            sweeps5[(int(m.group(1)), int(m.group(3) or 1))] = seconds_of(b)
    fast5_notes = []
    for (n, k), sweep in sorted(sweeps5.items()):
        if n not in memory or (n, k) not in floors:
            continue
        floor = sweep + floors[(n, k)]
        note = (f"{k} thread{'s' if k > 1 else ''}: sweep {sweep * 1e3:.1f} ms + rows {floors[(n, k)] * 1e3:.1f} ms = "
                f"{floor / memory[n]:.1f}× the memory pass")
        goal = goals[("fast5", "biharmonic")][0]
        solve = solves.get(("fast5", n, "biharmonic"), {}).get(k)
        if floor / memory[n] >= goal:
            note += f", which alone exceeds the goal (≤ {goal}×)"
        else:
            note += f", which leaves {goal - floor / memory[n]:.1f}× of the goal (≤ {goal}×) for the rest"
            if solve and solve[0] >= floor:
                note += f" of the solve (it takes {(solve[0] - floor) / memory[n]:.1f}× now)"
            elif solve:  # the twisted sweep transforms the rows on its way up: no separate pass
                note += (f" of the solve, which takes {solve[0] / memory[n]:.1f}× in all, less than these two "
                         "passes: on mask data its second sweep transforms each row on its way up "
                         "(solvers/fast5_twisted.h)")
        fast5_notes.append(f"N = {n}, {note}")
    if fast5_notes:
        text += ("\n\nThe floor of `fast5` on mask data, same run (`BM_Fast5Sweep`: one banded sweep of the grid, down "
                 "and up every mode's factors made beforehand, for the three columns; `BM_SineRows`: one row "
                 "transform; a `fast5` solve does both, besides its set-up and its capacitance solve): "
                 + "; ".join(fast5_notes) + ".")
    # mg per V-cycle: the whole solve's time over its cycles (to the benchmark's tolerance), so a
    # reader can tell the cost of a cycle from the number of cycles.
    per_cycle = []
    for (backend, n, alpha), by in sorted(solves.items()):
        if backend != "mg" or n not in memory:
            continue
        for k in sorted(by):
            c = cycles.get(((backend, n, alpha), k), 0)
            if c > 0:
                per_cycle.append(f"N = {n}, α = {alpha}, {k} thread{'s' if k > 1 else ''}: {c} cycles, "
                                 f"{by[k][0] / c / memory[n]:.0f}× the memory pass per cycle")
    if per_cycle:
        text += ("\n\n`mg` per V-cycle, same run (three right-hand sides to relative residual 1e−12: the wall time "
                 "of a fresh set-up and solve divided by its cycles, so the set-up is shared out among them): " + "; ".join(per_cycle) + ".")
    return text


def sizes_table(data, reference=1023):
    """One-thread solves at sizes around 2^k − 1 (N + 1 with large prime factors), as multiples of
    the memory pass of the same N and, per unknown, of the solve at N = reference."""
    memory, solves = memory_passes(data), {}
    for b in data["benchmarks"]:
        t = seconds_of(b)
        m = re.match(r"BM_Solve/([^/]+)/N:(\d+)/alpha:([^/]+)/min_time", b["name"])
        if m:  # one thread only
            solves[(m.group(1), int(m.group(2)))] = (t, m.group(3))
    out = ["| backend | N | α | wall | / memory pass | per unknown, / N = %d |" % reference, "|---|---|---|---|---|---|"]
    for (backend, n), (t, alpha) in sorted(solves.items()):
        base = solves.get((backend, reference))
        per = f"{(t / n**2) / (base[0] / reference**2):.2f}" if base else "–"
        mem = f"{t / memory[n]:.1f}×" if n in memory else "–"
        out.append(f"| `{backend}` | {n} | {alpha} | {t * 1e3:.1f} ms | {mem} | {per} |")
    return "\n".join(out)


def e2e_paragraph(e):
    """Issue 14's end-to-end target: `coons solve` of a 1001×1001 net in at most 2 s."""
    goal = 2.0
    wall = e["wall_seconds"]
    verdict = "met" if wall <= goal else missed_by(wall / goal)
    phases = ", ".join(f"{name} {seconds:.2f} s" for name, seconds in e["timing"].items())
    loads = ", ".join(f"{x:.1f}" for x in e.get("load_avg", []))
    return (f"End to end (`experiments/benchmarks/bench_solve_e2e.py`; run {e['date']}, load average at the start "
            f"{loads}): `coons solve` of the dome at degree {e['degree']} ({e['degree'] + 1}×{e['degree'] + 1} net, "
            f"`--solver {e['solver']} --threads {e.get('threads', 1)}`) took {wall:.2f} s wall and {e['cpu_seconds']:.2f} s of CPU, "
            f"{e['max_rss_mb']:.0f} MB at most, for a {e['report_mb']:.0f} MB report; its phases: {phases}. "
            f"Goal ≤ {goal:g} s: {verdict}.")


def main():
    parser = argparse.ArgumentParser(description="multigrid iteration and thread tables")
    parser.add_argument("--iterations", nargs="+", required=True)
    parser.add_argument("--threads")
    parser.add_argument("--e2e", nargs="+")
    parser.add_argument("--sizes")
    parser.add_argument("--docs")
    args = parser.parse_args()
    runs = [load(path) for path in args.iterations]
    mg = {"context": runs[0]["context"], "benchmarks": [b for r in runs for b in r["benchmarks"]]}
    notes = "; ".join(load_note(r) for r in runs)
    parts = [f"Iterations to relative residual 1e−10, three right-hand sides, one fresh set-up and solve "
             f"(`bench_solvers --mg-iterations`; {notes}; the seconds are wall-clock on the shared "
             f"machine):", "", iteration_table(mg)]
    if args.threads:
        th = load(args.threads)
        parts += ["", f"One and two threads (`SolverOptions::threads`; `bench_solvers --large --backends=fast,dst,mg,fast5,separable-banded`, the 5×5 problems in the α column; "
                      f"{load_note(th)}; tolerance 1e−12 for `mg`):", "", threads_table(th)]
    if args.sizes:
        sz = load(args.sizes)
        parts += ["", f"Sizes other than 2^k − 1, one thread (`bench_solvers --large --sizes=1000,1023,1024,1030 "
                      f"--backends=fast,dst`; {load_note(sz)}): N + 1 = 1001 = 7·11·13, 1025 = 5²·41 and 1031 "
                      f"(prime) are slow FFT lengths, which `fast` avoids by an interface of a few columns "
                      f"(solvers/capacitance.h) and `dst` does not:", "", sizes_table(sz)]
    if args.e2e:
        parts += ["", " ".join(e2e_paragraph(load(path)) for path in args.e2e)]
    text = "\n".join(parts) + "\n"
    if args.docs:
        with open(args.docs) as f:
            doc = f.read()
        if BEGIN not in doc or END not in doc:
            print(f"error: {args.docs}: markers {BEGIN} / {END} missing", file=sys.stderr)
            return 2
        head, rest = doc.split(BEGIN, 1)
        _, tail = rest.split(END, 1)
        with open(args.docs, "w") as f:
            f.write(head + BEGIN + "\n" + text + END + tail)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
