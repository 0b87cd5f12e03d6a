#!/usr/bin/env python3
"""E05 — Farin–Hansford's triangles: the best member c of the triangular mask family per shape,
objective and degree. Regenerates results/results.json, results/report.md and README.md:

    python3 experiments/E05_triangles/run.py [--coons ./build/coons]
    python3 experiments/E05_triangles/run.py --check   # the README's conclusions against results.json

For each bundled triangle (data/triangles/*.json) and each degree of DEGREES at or above the
file's own, the sides are degree-elevated exactly (a Bézier curve elevated; the triangle's
boundary is the same curves), written to a temporary file, and `coons search-alpha --objective X`
is run for X in OBJECTIVES (and `target` when the file has one). The conclusions are claims computed
from the table (claims()); each is rendered as a sentence only in the form its numbers support, and
--check recomputes every claim from results/results.json, fails when the README's conclusions
differ from the generated ones or a claim contradicts the table, and tampers the table once per
claim to show that the check can fail.

A second section compares the rectangular α family with the triangular c family on the same known
surface (the unit square split along its diagonal; question.md states exactly what is compared):
results/split.json, its conclusions checked the same way, and the figures results/split_distance.png
and results/optimal_c.png (gnuplot). Python 3 standard library only (and gnuplot)."""
import argparse
import copy
import datetime
import json
import pathlib
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
DEGREES = [6, 8, 12, 16]
OBJECTIVES = ["thin_plate", "e3", "dirichlet", "twist", "discrete_thin_plate"]

sys.path.insert(0, str(ROOT / "scripts"))
from make_triangles import elevate  # noqa: E402  (exact degree elevation of a Bézier side)


def search(coons, path, objective):
    r = subprocess.run([coons, "search-alpha", str(path), "--objective", objective], capture_output=True, text=True)
    if r.returncode not in (0, 3):
        raise SystemExit(f"{path} {objective}: exit {r.returncode}: {r.stderr.strip()}")
    return json.loads(r.stdout)


SAME_C = 0.02       # optima closer than this count as "the same c"
TWIST_FORMULA = 1e-8  # |c* - (-1/6 + 1/(4n - 6))| below this counts as "given by the formula"
AT_QUADRATIC = 1e-9   # |c* + 1/6| below this at every degree counts as "at -1/6" (a reproduced patch)


def interior(rows, shape, objective, degree):
    """The interior optimum c* of a cell, or None (flat, on a bound, failed, absent)."""
    hit = [r for r in rows if r["boundary"] == shape and r["objective"] == objective and r["degree"] == degree]
    if not hit or hit[0]["c"] is None or hit[0]["at_bound"] or hit[0]["flat"]:
        return None
    return hit[0]["c"]


def measure(rows, claim):
    """Recomputes what a claim is about from the table: the claim's numbers and whether it holds."""
    kind, objective = claim["kind"], claim.get("objective")
    shapes = sorted({r["boundary"] for r in rows})
    if kind == "spread":  # the interior optima of one objective at one degree, over the shapes
        d = claim["degree"]
        values = {s: interior(rows, s, objective, d) for s in shapes}
        values = {s: c for s, c in values.items() if c is not None}
        if len(values) < 2:
            return {"low": None, "high": None, "holds": False}
        low, high = min(values, key=values.get), max(values, key=values.get)
        return {"low": [low, round(values[low], 5)], "high": [high, round(values[high], 5)],
                "holds": values[high] - values[low] > SAME_C}
    if kind == "toward_quadratic":  # |c* + 1/6| decreases with the degree, shape by shape
        out, at = {}, []
        for s in shapes:
            cs = [(d, interior(rows, s, objective, d)) for d in DEGREES]
            cs = [(d, c) for d, c in cs if c is not None]
            if len(cs) >= 2:
                gaps = [abs(c + 1 / 6) for _, c in cs]
                if all(g <= AT_QUADRATIC for g in gaps):  # already there: rounding cannot decrease
                    at.append(s)
                    continue
                out[s] = all(b < a for a, b in zip(gaps, gaps[1:]))
        return {"shapes": sorted(out), "against": sorted(s for s, ok in out.items() if not ok), "at": at,
                "holds": bool(out) and all(out.values())}
    if kind == "on_bound":  # cells of an objective whose optimum sits on a search bound
        cells = sorted([r["boundary"], r["degree"]] for r in rows if r["objective"] == objective and r["at_bound"])
        total = sum(1 for r in rows if r["objective"] == objective)
        return {"cells": cells, "total": total, "holds": bool(cells)}
    if kind == "flat":
        cells = sorted([r["boundary"], r["degree"]] for r in rows if r["objective"] == objective and r["flat"])
        return {"cells": cells, "holds": bool(cells)}
    if kind == "twist_formula":  # shapes whose twist optimum is -1/6 + 1/(4n - 6) at every degree
        exact = []
        for s in shapes:
            cs = [(d, interior(rows, s, "twist", d)) for d in DEGREES]
            cs = [(d, c) for d, c in cs if c is not None]
            if cs and all(abs(c - (-1 / 6 + 1 / (4 * d - 6))) < TWIST_FORMULA for d, c in cs):
                exact.append(s)
        return {"exact": exact, "others": [s for s in shapes if s not in exact], "holds": bool(exact)}
    raise ValueError(kind)


def claims(rows):
    """The claims of the conclusions, each with the numbers measure() gives for it."""
    out = []
    top = max(r["degree"] for r in rows)
    for objective in ("thin_plate", "e3", "twist", "discrete_thin_plate", "target"):
        out.append(dict({"kind": "spread", "objective": objective, "degree": top},
                        **measure(rows, {"kind": "spread", "objective": objective, "degree": top})))
    for objective in ("thin_plate", "e3", "twist", "discrete_thin_plate", "target"):
        out.append(dict({"kind": "toward_quadratic", "objective": objective},
                        **measure(rows, {"kind": "toward_quadratic", "objective": objective})))
    out.append(dict({"kind": "on_bound", "objective": "dirichlet"},
                    **measure(rows, {"kind": "on_bound", "objective": "dirichlet"})))
    out.append(dict({"kind": "flat", "objective": "target"}, **measure(rows, {"kind": "flat", "objective": "target"})))
    out.append(dict({"kind": "twist_formula"}, **measure(rows, {"kind": "twist_formula"})))
    return out


def sentence(claim):
    """A claim in words: the form of the sentence follows the measured `holds`."""
    k, o, h = claim["kind"], claim.get("objective"), claim["holds"]
    if k == "spread":
        if claim["low"] is None:
            return f"At n = {claim['degree']}, fewer than two shapes have an interior {o} optimum."
        (ls, lc), (hs, hc) = claim["low"], claim["high"]
        verdict = (f"no single c is best for {o}" if h else f"one c serves every shape for {o} (within {SAME_C})")
        return (f"At n = {claim['degree']}, {verdict}: its interior optima run from {lc:.5f} ({ls}) to "
                f"{hc:.5f} ({hs}).")
    if k == "toward_quadratic":
        at = (f"; at −1/6 to {AT_QUADRATIC:g} at every degree: {', '.join(claim['at'])}" if claim.get("at") else "")
        if h:
            return (f"Every {o} optimum moves toward the quadratic-precision member −1/6 as the degree grows "
                    f"(|c* + 1/6| decreases from degree to degree for {', '.join(claim['shapes'])}{at}).")
        return (f"The {o} optima do not all approach −1/6 monotonically as the degree grows (against it: "
                f"{', '.join(claim['against']) or 'no shape with two interior optima'}{at}).")
    if k == "on_bound":
        where = ", ".join(f"{s} n = {d}" for s, d in claim["cells"]) or "none"
        if h:
            return (f"The {o} optimum lies on a search bound in {len(claim['cells'])} of {claim['total']} cells "
                    f"({where}): there the range does not contain its minimiser, and no best c is claimed.")
        return f"No {o} optimum lies on a search bound ({claim['total']} cells)."
    if k == "flat":
        if h:
            return (f"The {o} objective does not depend on c for " +
                    ", ".join(f"{s} n = {d}" for s, d in claim["cells"]) +
                    " (flat: every member keeps the planar net in its plane).")
        return f"No {o} objective is flat."
    if k == "twist_formula":
        if h:
            return (f"The twist optimum equals −1/6 + 1/(4n − 6) to {TWIST_FORMULA:g} at every degree for "
                    f"{', '.join(claim['exact'])}, and not for {', '.join(claim['others']) or 'any other shape'}: "
                    f"a pattern of these shapes, not a law.")
        return "No shape's twist optimum follows −1/6 + 1/(4n − 6) at every degree."
    raise ValueError(k)


def contradictions(rows, claim_list):
    """Claims whose numbers or verdict differ from what the table gives (empty: all consistent)."""
    bad = []
    for claim in claim_list:
        fresh = measure(rows, claim)
        for key, value in fresh.items():
            if claim.get(key) != value:
                bad.append(f"{claim['kind']} {claim.get('objective', '')}: {key} is {value}, the claim says "
                           f"{claim.get(key)}")
    return bad


def tampered(rows, claim):
    """A copy of the table changed so that `claim` no longer describes it (for the self-test)."""
    rows = copy.deepcopy(rows)
    k, o = claim["kind"], claim.get("objective")
    mine = [r for r in rows if r["objective"] == (o or "twist")]
    if k == "spread":
        for r in mine:
            if r["degree"] == claim["degree"] and r["c"] is not None and not r["at_bound"]:
                r["c"] = -0.15 if claim["holds"] else r["c"] + 0.1 * len(r["boundary"])
    elif k in ("toward_quadratic", "twist_formula"):
        for r in mine:
            if r["c"] is not None:
                r["c"] = -1 / 6 - 0.01 * r["degree"] if claim["holds"] else -1 / 6 + 1 / (4 * r["degree"] - 6)
    elif k == "on_bound":
        for r in mine:
            r["at_bound"] = not claim["holds"]
    elif k == "flat":
        for r in mine:
            r["flat"] = not claim["holds"]
    return rows


# ---- The square split along its diagonal: the rectangular α family against the triangular c family.
import split_square  # noqa: E402  (scripts/split_square.py: the boundaries, the sampling on T)

SPLIT_SHAPES = ["dome", "monkey_saddle"]
SPLIT_DEGREES = [4, 6, 8]
SCAN = 41  # members per family for the distance curves (figure)


def solve(coons, path, alpha):
    """The report of `coons solve PATH --alpha ALPHA`."""
    r = subprocess.run([coons, "solve", str(path), "--alpha", repr(alpha)], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{path} --alpha {alpha}: exit {r.returncode}: {r.stderr.strip()}")
    return json.loads(r.stdout)


def solve_net(coons, path, alpha):
    return solve(coons, path, alpha)["net"]


def golden(f, lo, hi, iterations=30):
    g = (5**0.5 - 1) / 2
    a, b = lo, hi
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(iterations):
        if f1 < f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - g * (b - a)
            f1 = f(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (b - a)
            f2 = f(x2)
    return (x1, f1) if f1 < f2 else (x2, f2)


def split_family(coons, path, family, shape, n, fixed):
    """One family on one boundary: the thin-plate optimum over its own domain (coons search-alpha),
    the RMS distance on T over the search range (SCAN members), its minimiser (golden section
    about the best scanned member), and distance and thin-plate energy on T at every member."""
    sampler = split_square.Sampler(family, n)
    report = search(coons, path, "thin_plate")
    lo, hi = report["bounds"]

    def rms(a):
        return sampler.distance(solve_net(coons, path, a), shape)[0]

    scan = [[lo + (hi - lo) * q / (SCAN - 1)] for q in range(SCAN)]
    for point in scan:
        point.append(rms(point[0]))
    best = min(range(SCAN), key=lambda q: scan[q][1])
    fit, _ = golden(rms, scan[max(best - 1, 0)][0], scan[min(best + 1, SCAN - 1)][0])
    members = dict(fixed, thin_plate_opt=report["alpha"], fit_opt=fit)
    out = {"bounds": [lo, hi], "scan": scan, "members": {}}
    for name, a in members.items():
        net = solve_net(coons, path, a)
        d_rms, d_max = sampler.distance(net, shape)
        at_bound = report["at_bound"] if name == "thin_plate_opt" else (
            name == "fit_opt" and min(abs(a - lo), abs(a - hi)) < 1e-6 * (hi - lo))
        out["members"][name] = {"alpha": a, "rms": d_rms, "max": d_max, "thin_plate_T": sampler.thin_plate(net),
                                "at_bound": at_bound}
    if family == "rectangle" and shape == "dome":  # symmetric about the other diagonal: E(T) = E(square)/2
        out["quadrature_check"] = {"exact_square": solve(coons, path, 0.0)["metrics"]["thin_plate_energy"],
                                   "twice_T": 2 * out["members"]["0"]["thin_plate_T"]}
    return out


def split_rows(coons, tmp):
    rows = []
    for shape in SPLIT_SHAPES:
        for n in SPLIT_DEGREES:
            rect, tri, errors = split_square.boundaries(shape, n)
            rpath, tpath = pathlib.Path(tmp) / f"{rect['name']}.json", pathlib.Path(tmp) / f"{tri['name']}.json"
            rpath.write_text(json.dumps(rect))
            tpath.write_text(json.dumps(tri))
            rows.append({"shape": shape, "degree": n, "fit_error": errors,
                         "rectangle": split_family(coons, rpath, "rectangle", shape, n, {"-1/4": -0.25, "0": 0.0}),
                         "triangle": split_family(coons, tpath, "triangle", shape, n, {"-1/6": -1 / 6, "0": 0.0})})
    return rows


def split_measure(rows, claim):
    """Recomputes a split claim from the table."""
    kind = claim["kind"]
    if kind == "split_fit":  # the best-fitting member of each family: which family is nearer s on T
        cells = {}
        for r in rows:
            a, c = r["rectangle"]["members"]["fit_opt"]["rms"], r["triangle"]["members"]["fit_opt"]["rms"]
            cells[f"{r['shape']} n = {r['degree']}"] = "rectangle" if a < c else "triangle"
        rect = sorted(k for k, v in cells.items() if v == "rectangle")
        return {"rectangle_better": rect, "total": len(cells), "holds": len(rect) == len(cells)}
    if kind == "split_precision":  # the precision members α = −1/4 and c = −1/6: which is nearer s on T
        rect = sorted(f"{r['shape']} n = {r['degree']}" for r in rows
                      if r["rectangle"]["members"]["-1/4"]["rms"] < r["triangle"]["members"]["-1/6"]["rms"])
        return {"rectangle_better": rect, "total": len(rows), "holds": len(rect) == len(rows)}
    if kind == "split_energy":  # the thin-plate optima: which net has the lower thin-plate energy on T
        cells = {}
        for r in rows:
            a = r["rectangle"]["members"]["thin_plate_opt"]["thin_plate_T"]
            c = r["triangle"]["members"]["thin_plate_opt"]["thin_plate_T"]
            cells[f"{r['shape']} n = {r['degree']}"] = "rectangle" if a < c else "triangle"
        rect = sorted(k for k, v in cells.items() if v == "rectangle")
        return {"rectangle_lower": rect, "total": len(cells), "holds": len(rect) == len(cells)}
    if kind == "split_tp_vs_fit":  # does the thin-plate optimum of the triangle fit s as well as its fit optimum
        ratios = {f"{r['shape']} n = {r['degree']}": round(r["triangle"]["members"]["thin_plate_opt"]["rms"] /
                                                              r["triangle"]["members"]["fit_opt"]["rms"], 3)
                  for r in rows if r["triangle"]["members"]["fit_opt"]["rms"] > 0}
        return {"worst": max(ratios.values()) if ratios else None, "holds": bool(ratios) and max(ratios.values()) < 1.5}
    raise ValueError(kind)


def split_claims(rows):
    return [dict({"kind": k}, **split_measure(rows, {"kind": k})) for k in ("split_fit", "split_precision", "split_energy", "split_tp_vs_fit")]


def cells_sentence(claim, key, holds, prefix, others):
    """A split claim over the cells: `holds` when the square's net wins in every cell, else `prefix`
    with the count and the cells `claim[key]` it wins in, and what `others` says of the rest."""
    if claim["holds"]:
        return f"{holds} in every one of the {claim['total']} cells."
    return (f"{prefix} in {len(claim[key])} of {claim['total']} cells ({', '.join(claim[key]) or 'none'}); "
            f"in the others {others}.")


def split_sentence(claim):
    k, h = claim["kind"], claim["holds"]
    if k == "split_fit":
        nearer = "the best-fitting α-net of the square is nearer the known surface than the best-fitting c-net of the triangle"
        return cells_sentence(claim, "rectangle_better", f"On the lower-left half T, {nearer}", f"On T, {nearer}",
                              "the triangle's is nearer")
    if k == "split_precision":
        nearer = "At the reference members, the α = −1/4 net is nearer the surface on T than the c = −1/6 net"
        return cells_sentence(claim, "rectangle_better", nearer, nearer, "the c = −1/6 net is nearer")
    if k == "split_energy":
        return cells_sentence(claim, "rectangle_lower",
                              "The α*-net (thin plate over the square) has a lower thin-plate energy on T than the "
                              "c*-net (thin plate over the triangle)",
                              "The α*-net (thin plate over the square) has the lower thin-plate energy on T",
                              "the c*-net's is lower")
    if k == "split_tp_vs_fit":
        if claim["worst"] is None:
            return "No triangle fits its surface inexactly, so the thin-plate and fit optima are not compared."
        if h:
            return (f"The triangle's thin-plate optimum c* is a good proxy for its best fit: its RMS distance is at "
                    f"most {claim['worst']:.3f} times the smallest over c.")
        return (f"The triangle's thin-plate optimum c* is not a proxy for its best fit: its RMS distance reaches "
                f"{claim['worst']:.3f} times the smallest over c.")
    raise ValueError(k)


def split_tampered(rows, claim):
    rows = copy.deepcopy(rows)
    key = {"split_fit": "rms", "split_precision": "rms", "split_energy": "thin_plate_T",
           "split_tp_vs_fit": "rms"}[claim["kind"]]
    member = {"split_energy": ("thin_plate_opt", "thin_plate_opt"),
              "split_precision": ("-1/4", "-1/6")}.get(claim["kind"], ("fit_opt", "fit_opt"))
    for r in rows:
        if claim["kind"] == "split_tp_vs_fit":
            r["triangle"]["members"]["thin_plate_opt"]["rms"] = r["triangle"]["members"]["fit_opt"]["rms"] * (
                2.0 if claim["holds"] else 1.0)
            continue
        a, c = r["rectangle"]["members"][member[0]], r["triangle"]["members"][member[1]]
        if claim["holds"]:
            a[key] = c[key] + 1.0
        else:
            a[key] = c[key] / 2
    return rows


def split_markdown(rows):
    lines = ["## The square split along its diagonal: α against c", "",
             "Per shape and degree n: the sides' largest fit errors, then for each family the members compared on "
             "T = {u + v ≤ 1}: the value of α (square) or c (triangle), the RMS and largest distance of the filling "
             "from the known surface at 1600 points of T, and the thin-plate energy ∫_T |F_uu|² + 2|F_uv|² + |F_vv|² "
             "du dv. `tp*` is the thin-plate optimum over the family's own domain (`coons search-alpha "
             "--objective thin_plate`: the whole square for α, the triangle for c), `fit*` the member nearest the "
             "surface on T (RMS, golden section).", ""]
    for r in rows:
        e = r["fit_error"]
        lines += [f"### {r['shape']}, n = {r['degree']}", "",
                  f"Fit errors (largest deviation of the Bézier side from s): bottom {e['bottom']:.2e}, left "
                  f"{e['left']:.2e}, top {e['top']:.2e}, right {e['right']:.2e}, diagonal {e['diagonal']:.2e}.", "",
                  "| family | member | α or c | RMS distance on T | max distance on T | thin plate on T |",
                  "|---|---|---|---|---|---|"]
        for family in ("rectangle", "triangle"):
            for name, m in r[family]["members"].items():
                mark = " (bound)" if m["at_bound"] else ""
                lines.append(f"| {family} | {name} | {m['alpha']:.5f}{mark} | {m['rms']:.3e} | {m['max']:.3e} | "
                             f"{m['thin_plate_T']:.5g} |")
        q = r["rectangle"].get("quadrature_check")
        if q:
            lines += ["", f"Quadrature check (the dome is symmetric about the other diagonal): twice the thin plate "
                          f"on T of the α = 0 net is {q['twice_T']:.6g}, its exact energy over the square "
                          f"(`coons solve`) {q['exact_square']:.6g} (relative difference "
                          f"{abs(q['twice_T'] / q['exact_square'] - 1):.1e})."]
        lines.append("")
    lines += ["![RMS distance from the surface on T over the member of each family](results/split_distance.png)", "",
              "### Conclusions of this section, computed from the table", ""]
    lines += [f"- {split_sentence(c)}" for c in split_claims(rows)]
    return "\n".join(lines) + "\n"


def gnuplot(script, data):
    """Runs a gnuplot script, then removes the data files it plotted."""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    for path in data:
        path.unlink()


def split_figure(rows, out):
    """results/split_distance.png: RMS distance on T against α (square) and c (triangle), one panel per
    shape at the top degree, the compared members marked."""
    top = max(SPLIT_DEGREES)
    data, panels = [], []
    for r in [r for r in rows if r["degree"] == top]:
        plots = []
        for family in ("rectangle", "triangle"):
            name = out / f"split_{r['shape']}_{family}.dat"
            name.write_text("".join(f"{a:.6g} {d:.6g}\n" for a, d in r[family]["scan"]))
            data.append(name)
            plots.append(f"'{name}' with linespoints title '{family} ({'α' if family == 'rectangle' else 'c'})'")
            name = out / f"split_{r['shape']}_{family}_members.dat"
            name.write_text("".join(f"{m['alpha']:.6g} {m['rms']:.6g}\n" for m in r[family]["members"].values()))
            data.append(name)
            plots.append(f"'{name}' with points pt 7 ps 1.5 title '{family}: reference members, tp*, fit*'")
        panels.append(f"set title '{r['shape']}, n = {top}'\nplot " + ", ".join(plots) + "\n")
    script = (f"set terminal pngcairo noenhanced size 1200,550\nset output '{out / 'split_distance.png'}'\n"
              "set multiplot layout 1,2\nset xlabel 'member (α for the square, c for the triangle)'\n"
              "set ylabel 'RMS distance from the surface on T'\nset logscale y\nset format y '%.0e'\n"
              "set key outside below\n" + "".join(panels) + "unset multiplot\n")
    gnuplot(script, data)


def optimum_figure(rows, out):
    """results/optimal_c.png: the interior thin-plate and target optima c* against the degree, per shape."""
    data, plots = [], []
    for shape in sorted({r["boundary"] for r in rows}):
        for objective in ("thin_plate", "target"):
            points = sorted((r["degree"], r["c"]) for r in rows if r["boundary"] == shape and
                            r["objective"] == objective and r["c"] is not None and not r["at_bound"] and not r["flat"])
            if not points:
                continue
            name = out / f"opt_{shape}_{objective}.dat"
            name.write_text("".join(f"{d} {c:.8g}\n" for d, c in points))
            data.append(name)
            plots.append(f"'{name}' with linespoints title '{shape} {objective}'")
    script = (f"set terminal pngcairo noenhanced size 900,600\nset output '{out / 'optimal_c.png'}'\n"
              "set xlabel 'degree n'\nset ylabel 'optimal c'\nset key outside below\n"
              "set title 'Interior optima c* of the triangular family (−1/6: quadratic precision)'\n"
              "plot " + ", ".join(plots) + ", -1.0/6 with lines dashtype 2 title 'c = −1/6'\n")
    gnuplot(script, data)


def conclusions_markdown(claim_list):
    return "\n".join(["## Conclusions, computed from the table", "",
                      "Each sentence is generated from `results/results.json` in the form its numbers support; "
                      "`run.py --check` recomputes them and fails on any contradiction.", ""] +
                     [f"- {sentence(c)}" for c in claim_list]) + "\n"


def check():
    rows = json.loads((HERE / "results" / "results.json").read_text())
    claim_list = claims(rows)
    problems = contradictions(rows, claim_list)
    readme = (HERE / "README.md").read_text()
    if conclusions_markdown(claim_list) not in readme:
        problems.append("README.md's conclusions are not those the table gives (rerun run.py)")
    for claim in claim_list:  # the check can fail: a table that contradicts each claim is caught
        if not contradictions(tampered(rows, claim), [claim]):
            problems.append(f"self-test: a table contradicting '{sentence(claim)}' was not caught")
    split = json.loads((HERE / "results" / "split.json").read_text())
    split_list = split_claims(split)
    for claim in split_list:
        for key, value in split_measure(split, claim).items():
            if claim.get(key) != value:
                problems.append(f"{claim['kind']}: {key} is {value}, the claim says {claim.get(key)}")
        changed = split_tampered(split, claim)
        if split_measure(changed, claim) == {k: claim[k] for k in split_measure(changed, claim)}:
            problems.append(f"self-test: a table contradicting '{split_sentence(claim)}' was not caught")
    if split_markdown(split) not in readme:
        problems.append("README.md's split section is not the one results/split.json gives (rerun run.py)")
    for p in problems:
        print("E05 check:", p)
    print(f"E05 check: {len(claim_list) + len(split_list)} conclusions, {len(problems)} problems")
    raise SystemExit(1 if problems else 0)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coons", default=str(ROOT / "build" / "coons"))
    parser.add_argument("--check", action="store_true", help="check README's conclusions against results.json")
    args = parser.parse_args()
    if args.check:
        check()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for file in sorted((ROOT / "data" / "triangles").glob("*.json")):
            doc = json.loads(file.read_text())
            n0 = len(doc["sides"][0]) - 1
            objectives = OBJECTIVES + (["target"] if "target" in doc else [])
            for n in [d for d in DEGREES if d >= n0]:
                elevated = dict(doc, degree=n, sides=[elevate(s, n - n0) for s in doc["sides"]])
                path = pathlib.Path(tmp) / f"{doc['name']}-{n}.json"
                path.write_text(json.dumps(elevated))
                for objective in objectives:
                    report = search(args.coons, path, objective)
                    rows.append({"boundary": doc["name"], "degree": n, "objective": objective,
                                 "c": report["alpha"], "value": report["value"], "bounds": report["bounds"],
                                 "flat": report["flat"], "at_bound": report["at_bound"],
                                 "status": report["status"], "evaluations": report["evaluations"]})
        split = split_rows(args.coons, tmp)
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "results.json").write_text(json.dumps(rows, indent=1) + "\n")
    (out / "split.json").write_text(json.dumps(split, indent=1) + "\n")
    split_figure(split, out)
    optimum_figure(rows, out)

    def fmt(row):
        if row["c"] is None:
            return row["status"]
        mark = " (bound)" if row["at_bound"] else ""
        return f"{row['c']:.5f}{mark}"

    lines = ["## Results", "",
             f"Computed {datetime.date.today().isoformat()} by `python3 experiments/E05_triangles/run.py` "
             f"(every number below is in `results/results.json`). The optimal c per shape, objective "
             f"(rows) and degree (columns); `target` is the mean squared distance to the file's analytic surface.", ""]
    shapes = sorted({r["boundary"] for r in rows})
    for shape in shapes:
        mine = [r for r in rows if r["boundary"] == shape]
        degrees = sorted({r["degree"] for r in mine})
        lines += [f"### {shape}", "", "| objective | " + " | ".join(f"n = {d}" for d in degrees) + " |",
                  "|---|" + "---|" * len(degrees)]
        for objective in dict.fromkeys(r["objective"] for r in mine):
            cells = []
            for d in degrees:
                hit = [r for r in mine if r["degree"] == d and r["objective"] == objective]
                cells.append(fmt(hit[0]) if hit else "")
            lines.append(f"| {objective} | " + " | ".join(cells) + " |")
        bounds = sorted({tuple(r["bounds"]) for r in mine})
        lines += ["", "Search bounds: " + ", ".join(f"n = {d}: [{b[0]:.4f}, {b[1]:.4f}]" for d, b in
                                                     sorted({(r['degree'], tuple(r['bounds'])) for r in mine})), ""]
    lines += ["![The interior thin-plate and target optima c* against the degree](results/optimal_c.png)", ""]
    # Patterns looked for in the numbers above (computed, not assumed).
    lines += ["## Checks", "",
              "Distance of each optimum from −1/6 (the quadratic-precision member), and of the twist optimum from "
              "−1/6 + 1/(4n − 6), a formula read off the monkey saddle and the planar triangle; a dash marks a "
              "search without an interior optimum (flat or at a bound).", "",
              "| shape | objective | " + " | ".join(f"n = {d}" for d in DEGREES) + " |",
              "|---|---|" + "---|" * len(DEGREES)]
    for shape in shapes:
        for objective in ("thin_plate", "e3", "twist", "twist vs -1/6+1/(4n-6)", "target"):
            name = objective.split(" ")[0]
            cells, any_hit = [], False
            for d in DEGREES:
                hit = [r for r in rows if r["boundary"] == shape and r["degree"] == d and r["objective"] == name]
                if not hit:
                    cells.append("")
                    continue
                any_hit = True
                r = hit[0]
                if r["c"] is None or r["at_bound"]:
                    cells.append("–")
                    continue
                reference = -1 / 6 + (1 / (4 * d - 6) if " vs " in objective else 0)
                cells.append(f"{r['c'] - reference:+.2e}")
            if any_hit:
                lines.append(f"| {shape} | {objective} | " + " | ".join(cells) + " |")
    report = "\n".join(lines) + "\n\n" + conclusions_markdown(claims(rows)) + "\n" + split_markdown(split)
    (out / "report.md").write_text(report.replace("](results/", "]("))  # links relative to results/
    question = (HERE / "question.md").read_text()
    (HERE / "README.md").write_text(question.rstrip() + "\n\n" + report)


if __name__ == "__main__":
    main()
