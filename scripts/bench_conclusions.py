#!/usr/bin/env python3
"""E03's conclusions, computed from its Markdown tables (the ones bench_report.py writes).

Every conclusion is a claim with the numbers it rests on; `holds` re-reads those numbers from the
tables, so a conclusion that contradicts its table is caught. The conclusions are made from the
parsed tables alone, so the README can be checked (and regenerated) without rerunning anything.
Usage:
  bench_conclusions.py --write README.md      (re)writes the conclusions section from the tables
  bench_conclusions.py --check README.md      exit 1 if the README's conclusions differ from the ones
                                               its tables give, or one of them does not hold
  bench_conclusions.py --self-test README.md  exit 1 unless a tampered table is caught
(standard library only)
"""
import math
import re
import sys

HEADER = "Conclusions (computed from the tables)"
STRUCTURED = ("fast", "dst", "auto")


def parse_tables(text):
    """{section heading: [row dicts keyed by the header cells]} for every Markdown table."""
    tables, heading, header = {}, None, None
    for line in text.splitlines():
        m = re.match(r"#+ (.*)", line)
        if m:
            heading, header = m.group(1).strip(), None
            continue
        if not line.startswith("|") or heading is None:
            header = None if not line.startswith("|") else header
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if header is None:
            header = cells
        elif set("".join(cells)) <= set("-: "):
            continue
        else:
            tables.setdefault(heading, []).append(dict(zip(header, cells)))
    return tables


def seconds_of(cell):
    """'0.0146 s (1.8×) ...' -> 0.0146; None for '–' or a failed run (✗)."""
    if not cell or "✗" in cell:
        return None
    m = re.match(r"([0-9.eE+-]+) s", cell)
    return float(m.group(1)) if m else None


def iterations_of(cell):
    m = re.search(r"(\d+) it", cell or "")
    return int(m.group(1)) if m and "✗" not in cell else None


def number(cell):
    m = re.match(r"\s*([0-9.eE+-]+)", cell or "")
    try:
        return float(m.group(1)) if m else None
    except ValueError:
        return None


def alpha_sections(tables):
    return sorted((h for h in tables if h.startswith("α = ")), key=lambda h: float(h[4:]))


def size_columns(rows):
    return sorted((k for k in rows[0] if k.startswith("N=")), key=lambda k: int(k[2:]))


def fastest(rows, column, exclude=()):
    # "fast (2 threads)" is the backend "fast" on two threads: excluded with it
    times = [(seconds_of(r.get(column)), r["backend"]) for r in rows if r["backend"].split(" (")[0] not in exclude]
    times = [t for t in times if t[0] is not None]
    return min(times) if times else None


def claims(tables):
    """[(sentence, check)], check(tables) -> bool re-reads the numbers the sentence states."""
    out = []
    for h in alpha_sections(tables):
        rows = tables[h]
        cols = size_columns(rows)
        big = next((c for c in reversed(cols) if any(seconds_of(r.get(c)) for r in rows)), None)
        if big is None:
            continue
        t, who = fastest(rows, big)

        def check_fastest(tb, h=h, big=big, who=who):
            best = fastest(tb[h], big)
            return best is not None and best[1] == who

        sentence = f"{h}: at the largest net measured ({big.replace('N=', 'N = ')}) the fastest backend is `{who}` ({t:.3g} s)"
        direct_col = next((c for c in reversed(cols)
                           if fastest(rows, c, STRUCTURED) is not None), None)
        if direct_col:
            dt, dwho = fastest(rows, direct_col, STRUCTURED)
            st = fastest(rows, direct_col)
            sentence += (f"; the fastest backend that is not a sine-transform solver, at {direct_col.replace('N=', 'N = ')}, "
                         f"is `{dwho}` ({dt:.3g} s, {dt / st[0]:.0f}× the fastest)")

            def check_direct(tb, h=h, c=direct_col, dwho=dwho):
                best = fastest(tb[h], c, STRUCTURED)
                return best is not None and best[1] == dwho
        else:
            def check_direct(tb):
                return True
        out.append((sentence + ".", lambda tb, a=check_fastest, b=check_direct: a(tb) and b(tb)))

        # exponents: near-linear (≤ 1.15) or not
        exps = {r["backend"]: number(r.get("exponent")) for r in rows if number(r.get("exponent")) is not None}
        if exps:
            linear = sorted(b for b, e in exps.items() if e <= 1.15)
            steeper = sorted(((e, b) for b, e in exps.items() if e > 1.15), reverse=True)
            parts = []
            if linear:
                parts.append("time grows about linearly in the unknowns (exponent ≤ 1.15) for "
                             + ", ".join(f"`{b}`" for b in linear))
            if steeper:
                parts.append("faster for " + ", ".join(f"`{b}` ({e:.2f})" for e, b in steeper))
            if parts:
                def check_exp(tb, h=h, linear=tuple(linear), steeper=tuple(b for _, b in steeper)):
                    e = {r["backend"]: number(r.get("exponent")) for r in tb[h]}
                    return all(e.get(b) is not None and e[b] <= 1.15 for b in linear) and \
                        all(e.get(b) is not None and e[b] > 1.15 for b in steeper)
                out.append((f"{h}: " + "; ".join(parts) + ".", check_exp))

        cg = next((r for r in rows if r["backend"] == "cg"), None)
        if cg:
            its = [(int(c[2:]), iterations_of(cg.get(c))) for c in cols]
            its = [(n, i) for n, i in its if i]
            if len(its) >= 2:
                growth = [(i2 / i1) ** (1 / math.log2(n2 / n1)) for (n1, i1), (n2, i2) in zip(its, its[1:])]
                lo, hi = min(growth), max(growth)
                verdict = ("grow about in proportion to N" if 1.8 <= lo and hi <= 2.2 else
                           "grow about as N²" if 3.6 <= lo and hi <= 4.4 else "grow")
                factor = f"×{lo:.2f}" if f"{lo:.2f}" == f"{hi:.2f}" else f"×{lo:.2f}–×{hi:.2f}"
                sentence = (f"{h}: plain CG's iterations {verdict}: {factor} per doubling of N "
                            f"({', '.join(str(i) for _, i in its)}).")

                def check_cg(tb, h=h, its=tuple(its)):
                    r = next((r for r in tb[h] if r["backend"] == "cg"), None)
                    return r is not None and all(iterations_of(r.get(f"N={n}")) == i for n, i in its)
                out.append((sentence, check_cg))

    target_h = next((h for h in tables if h.startswith("Targets at N")), None)
    if target_h:
        rows = tables[target_h]
        met = [r["target"] for r in rows if r["met"] == "yes"]
        missed = [(r["target"], r["met"]) for r in rows if r["met"].startswith("no")]
        sentence = f"{target_h.split(' (')[0]}: {len(met)} of {len(rows)} targets met"
        if missed:
            sentence += "; not met: " + "; ".join(f"{t} ({m[3:].strip('()')})" for t, m in missed)

        def check_targets(tb, h=target_h, n_met=len(met), n=len(rows)):
            rs = tb[h]
            ok = True
            for r in rs:
                achieved, goal = number(r["achieved"]), number(r["goal"].lstrip("≤ "))
                if achieved is not None and goal is not None:
                    ok &= (achieved <= goal) == (r["met"] == "yes")
            return ok and len(rs) == n and sum(r["met"] == "yes" for r in rs) == n_met
        out.append((sentence + ".", check_targets))

    search_h = next((h for h in tables if h.startswith("α search")), None)
    if search_h:
        rows = tables[search_h]
        col = "(search + net) / one solve"
        by = {}
        for r in rows:
            if number(r.get(col)) is not None:
                by.setdefault(r["backend"], []).append((int(r["N"]), number(r[col])))
        sine = next((b for b in by if "sine basis" in b), None)
        solve = next((b for b in by if "solve per evaluation" in b), None)
        if sine and solve:
            n = max(set(x for x, _ in by[sine]) & set(x for x, _ in by[solve]), default=None)
            if n:
                a, b = dict(by[sine])[n], dict(by[solve])[n]
                sentence = (f"The α search with its optimal net costs {a:.1f} solves in the sine basis against {b:.1f} "
                            f"solving per evaluation at N = {n} ({b / a:.0f}× more)")
                rng = [v for _, v in by[sine]]
                sentence += f"; in the sine basis it stays between {min(rng):.1f} and {max(rng):.1f} solves over N = " \
                            f"{min(x for x, _ in by[sine])} … {max(x for x, _ in by[sine])}."

                def check_search(tb, h=search_h, sine=sine, solve=solve, n=n, a=a, b=b):
                    got = {(r["backend"], int(r["N"])): number(r.get(col)) for r in tb[h]}
                    return got.get((sine, n)) == a and got.get((solve, n)) == b and a < b
                out.append((sentence, check_search))

    refactor_h = next((h for h in tables if h.startswith("Analysis reused")), None)
    if refactor_h:
        rows = [r for r in tables[refactor_h] if number(r.get("ratio")) is not None]
        if rows:
            lo = min(rows, key=lambda r: number(r["ratio"]))
            hi = max(rows, key=lambda r: number(r["ratio"]))
            sentence = (f"Reusing the analysis (refactorize) costs {number(lo['ratio']):.2f}–{number(hi['ratio']):.2f} "
                        f"of a fresh solve at the largest N: most saved by `{lo['backend']}` at α = {lo['α']}, "
                        f"least by `{hi['backend']}` at α = {hi['α']}")
            no_gain = sorted({r["backend"] for r in rows if number(r["ratio"]) > 1})
            sentence += ("; no gain (ratio above 1) somewhere for " + ", ".join(f"`{b}`" for b in no_gain) + "."
                         if no_gain else ".")

            def check_refactor(tb, h=refactor_h, lo=number(lo["ratio"]), hi=number(hi["ratio"])):
                rs = [number(r.get("ratio")) for r in tb[h] if number(r.get("ratio")) is not None]
                return bool(rs) and min(rs) == lo and max(rs) == hi
            out.append((sentence, check_refactor))
    return out


def conclusions_markdown(tables):
    return f"### {HEADER}\n\n" + "".join(f"- {s}\n" for s, _ in claims(tables))


def split_readme(text):
    """(the text before the conclusions, the conclusions section or None)."""
    marker = f"### {HEADER}"
    if marker not in text:
        return text, None
    before, after = text.split(marker, 1)
    section, rest = after, ""
    m = re.search(r"\n(?=#|!\[)", after.lstrip("\n"))
    if m:
        body = after.lstrip("\n")
        section, rest = body[:m.start() + 1], body[m.start() + 1:]
    return before + rest, marker + "\n\n" + section.strip("\n") + "\n"


def check(text):
    """Problems: a conclusion that does not hold, or a conclusions section that differs from the tables'."""
    tables = parse_tables(text)
    problems = [f"does not hold: {s}" for s, holds in claims(tables) if not holds(tables)]
    _, section = split_readme(text)
    if section is None:
        problems.append(f"no '{HEADER}' section")
    elif section.strip() != conclusions_markdown(tables).strip():
        problems.append("the conclusions differ from the ones the tables give (regenerate: bash scripts/bench.sh "
                        "--report-only)")
    return problems


def write(path):
    """Puts the conclusions its tables give into the README, before the figures (replacing old ones)."""
    text = open(path, encoding="utf-8").read()
    rest, _ = split_readme(text)
    section = conclusions_markdown(parse_tables(rest))
    at = rest.find("\n![")
    at = len(rest) if at < 0 else at + 1
    text = rest[:at].rstrip("\n") + "\n\n" + section + "\n" + rest[at:]
    open(path, "w", encoding="utf-8").write(text.rstrip("\n") + "\n")


def self_test(text):
    """The check passes on the README and fails once a table cell contradicts a conclusion."""
    if check(text):
        return ["the README itself fails the check"]
    tables = parse_tables(text)
    cs = claims(tables)
    if not cs:
        return ["no conclusions to test"]
    # Tamper: make the claimed fastest backend at the largest N of the first α section slow.
    h = alpha_sections(tables)[0]
    cols = size_columns(tables[h])
    big = next(c for c in reversed(cols) if any(seconds_of(r.get(c)) for r in tables[h]))
    winner = fastest(tables[h], big)[1]
    for r in tables[h]:
        if r["backend"] == winner:
            r[big] = "1e9 s (1×)"
    if all(holds(tables) for _, holds in cs):
        return ["a tampered table was not caught"]
    # Tamper with a conclusion instead: its text no longer follows from the tables.
    rest, section = split_readme(text)
    edited = section.replace(f"`{winner}`", "`cg`", 1)
    if edited == section or not check(rest + "\n" + edited):
        return ["a tampered conclusion was not caught"]
    return []


def main():
    mode, path = sys.argv[1], sys.argv[2]
    if mode == "--write":
        write(path)
        return 0
    text = open(path, encoding="utf-8").read()
    problems = check(text) if mode == "--check" else self_test(text) if mode == "--self-test" else ["unknown mode"]
    for p in problems:
        print(f"error: {path}: conclusions: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
