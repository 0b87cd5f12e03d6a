#!/usr/bin/env python3
"""Checks that keep coons's documentation from drifting away from the repository.

    python3 scripts/check_docs.py schemas      # every bundled data file validates against its schema
    python3 scripts/check_docs.py links        # every relative link in every tracked Markdown file resolves
    python3 scripts/check_docs.py selfcontained  # no tracked file points outside the repository
    python3 scripts/check_docs.py reference    # data/reference/*.json recomputed from first principles
    python3 scripts/check_docs.py tests        # every test that docs/*.md, README.md and data/README.md cite exists
    python3 scripts/check_docs.py all

Each check prints one line per finding and a summary; the exit status is 1 when anything fails.
The schemas are under docs/schema/ (JSON Schema draft 2020-12, checked with python3-jsonschema);
the formats they describe are in docs/formats.md. Standard library only, except `schemas`.
"""
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def tracked_files(pattern=None):
    """Files tracked by git (or every file under ROOT when this is not a git checkout)."""
    try:
        out = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z"], check=True, capture_output=True).stdout
        files = [ROOT / f for f in out.decode().split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = [p for p in ROOT.rglob("*") if p.is_file() and ".git" not in p.parts and "build" not in p.parts]
    files = [f for f in files if f.exists()]
    if pattern:
        files = [f for f in files if re.search(pattern, f.name)]
    return files


# ---- schemas ------------------------------------------------------------------------------------

# Which schema each bundled data file must satisfy (every JSON file under data/ needs one).
SCHEMA_OF_FOLDER = {
    "data/boundaries": ["boundary.schema.json"],
    "data/surfaces": ["surface.schema.json"],
    "data/reference": ["reference.schema.json"],
    "data/triangles": ["triangle.schema.json"],
    "data/free_sets": ["boundary.schema.json", "net.schema.json"],
}

P = [0.0, 0.0, 0.0]
GOOD_BOUNDARY = {"name": "unit", "degree": [1, 1], "bottom": [[0, 0, 0], [1, 0, 0]], "top": [[0, 1, 0], [1, 1, 0]],
                 "left": [[0, 0, 0], [0, 1, 0]], "right": [[1, 0, 0], [1, 1, 0]]}


def with_(doc, **changes):
    out = json.loads(json.dumps(doc))
    for k, v in changes.items():
        if v is None:
            out.pop(k, None)
        else:
            out[k] = v
    return out


# Documents that must be accepted (so the schemas are not too strict) ...
ACCEPTED = [
    ("boundary.schema.json", GOOD_BOUNDARY, "the sides form"),
    ("boundary.schema.json", {"net": [[P, P], [P, P]]}, "the net form"),
    ("triangle.schema.json", {"type": "triangle", "degree": 1, "sides": [[P, P], [P, P], [P, P]]}, "a triangle"),
    ("boundary.schema.json", {"net": [[P, P], [P, P]], "rings": 1, "free": [[0, 0], [0, False]]},
     "the net form with rings and a free grid"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, ribbons={s: [P, P] for s in ("bottom", "top", "left", "right")}),
     "the sides form with ribbons (their lengths and ends are the reader's to check)"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, extension="coons ignores it"), "an unknown field (ignored by coons)"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"plane": {"point": P, "normal": [0, 0, 1]}}), "a plane target"),
    ("net.schema.json", {"name": "n", "degree": [1, 1], "exact": True, "net": [[P, P], [P, P]]}, "coons surface --net-out"),
    ("surface.schema.json", {"type": "ruled", "curves": [{"bezier": [P, [1, 0, 0]]},
                                                          {"expr": ["t", "1", "sin(pi*t)"], "interval": [0, 1]}]},
     "a ruled surface of a Bezier and an expression curve"),
    ("surface.schema.json", {"type": "sectorial", "curve": {"hermite": [P, [1, 0, 0], [1, 0, 0], [1, 0, 0]]},
                             "point": [0, 0, 1], "comment": "x"}, "a sectorial surface of a Hermite cubic"),
    ("boundary.schema.json", {"net": [[P, P], [P, P]], "bottom": [[0, 0]]}, "the net form with a broken side (sides are not read)"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"sphere": {"center": P, "radius": 1}, "plane": {}}),
     "a sphere target with a broken plane (only the first of sphere, cylinder, plane is read)"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, description=["not", "read"]), "a description that is not a string"),
    ("surface.schema.json", {"type": "bilinear", "corners": [P, P, P, P], "comment": 3}, "a comment that is not a string"),
]

# ... and documents that must be rejected (so the check can fail).
REJECTED = [
    ("boundary.schema.json", with_(GOOD_BOUNDARY, top=None), "a missing side"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, bottom=[[0, 0], [1, 0, 0]]), "a point of 2 coordinates"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, bottom=[[0, 0, "0"], [1, 0, 0]]), "a coordinate that is a string"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, bottom=[[0, 0, 0]]), "a side of one point (degree 0)"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, degree=[3]), "a degree of one number"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, degree=[1.5, 1]), "a degree that is not an integer"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, name=7), "a name that is not a string"),
    ("boundary.schema.json", {"net": [[P, P]]}, "a net of one row"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, ribbons={"bottom": [P, P]}), "ribbons without top, left, right"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, rings=2), "rings in the sides form"),
    ("boundary.schema.json", {"net": [[P, P], [P, P]], "free": [[0, 2], [0, 0]]}, "a free flag of 2"),
    ("boundary.schema.json", {"net": [[P, P], [P, P]], "rings": 0}, "rings 0"),
    ("boundary.schema.json", {"net": [[P, P], [P, P]], "ribbons": {}}, "ribbons in the net form"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"sphere": {"center": P}}), "a sphere without a radius"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"sphere": {"center": P, "radius": -1}}), "a negative radius"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"torus": {}}), "an unknown target"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, curves={"bottom": {"bezier": [P]}}), "curves without top, left, right"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, curves={s: {"bezier": [P], "expr": ["t", "t", "t"]}
                                                           for s in ("bottom", "top", "left", "right")}),
     "a curve with two forms"),
    ("net.schema.json", {"name": "n"}, "a net file without a net"),
    ("triangle.schema.json", {"type": "triangle", "sides": [[P, P], [P, P]]}, "a triangle of two sides"),
    ("triangle.schema.json", {"type": "quad", "sides": [[P, P], [P, P], [P, P]]}, "a type that is not triangle"),
    ("triangle.schema.json", {"type": "triangle", "sides": [[P, P], [P, P], [P, [0, 0]]]}, "a point of 2 coordinates"),
    ("surface.schema.json", {"curves": []}, "no type"),
    ("surface.schema.json", {"type": "torus"}, "an unknown type"),
    ("surface.schema.json", {"type": "bilinear", "corners": [P, P, P]}, "three corners"),
    ("surface.schema.json", {"type": "bilinear", "corners": [P, P, P, P], "description": "x"},
     "a field the type does not use (surface_io.cpp rejects it)"),
    ("surface.schema.json", {"type": "ruled", "curves": [{"bezier": [P]}, {"expr": ["t", "t"]}]},
     "an expression curve of two components"),
    ("surface.schema.json", {"type": "ruled", "curves": [{"bezier": [P]}, {"bezier": [P], "interval": [0, 1]}]},
     "an interval on a Bezier curve"),
    ("surface.schema.json", {"type": "ferguson", "corners": [P, P, P, P], "du": [P, P, P, P]}, "ferguson without dv"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"plane": {"point": P, "normal": [0, 0, 0]}}), "a zero plane normal"),
    ("boundary.schema.json", with_(GOOD_BOUNDARY, target={"sphere": 5}), "a sphere that is not an object"),
    ("surface.schema.json", {"type": "conoid", "directrix": {"point": P}, "line": [P, [0, 0, 0]], "plane_normal": [0, 0, 1]},
     "a conoid whose line has no direction"),
]

# The bundled files document themselves: what each one is and where it comes from (coons does not
# read these fields, so the schemas accept any value; here the data files are held to strings).
DOCUMENTED_BY = {"data/boundaries": ["description", "source"], "data/surfaces": ["source"],
                 "data/free_sets": ["description", "source"]}


def check_schemas():
    try:
        import jsonschema
    except ImportError:
        print("error: check_docs.py schemas: python3-jsonschema is missing (apt-get install python3-jsonschema)")
        return 1
    validator_class = jsonschema.Draft202012Validator
    schema_dir = ROOT / "docs" / "schema"
    schemas = {}
    failures = 0
    for path in sorted(schema_dir.glob("*.schema.json")):
        schema = json.loads(path.read_text())
        validator_class.check_schema(schema)
        schemas[path.name] = validator_class(schema)

    def errors(name, doc):
        return sorted(schemas[name].iter_errors(doc), key=lambda e: list(e.path))

    validated = 0
    for folder, names in SCHEMA_OF_FOLDER.items():
        for path in sorted((ROOT / folder).glob("*.json")):
            doc = json.loads(path.read_text())
            use = list(names)
            if folder == "data/boundaries" and isinstance(doc, dict) and "net" in doc:
                use.append("net.schema.json")
            for name in use:
                found = errors(name, doc)
                for e in found[:3]:
                    print(f"FAIL {path.relative_to(ROOT)}: {name}: {'/'.join(map(str, e.path)) or '(top)'}: {e.message[:200]}")
                failures += bool(found)
            for field in DOCUMENTED_BY.get(folder, []):
                if not isinstance(doc, dict) or not isinstance(doc.get(field), str) or not doc[field].strip():
                    print(f"FAIL {path.relative_to(ROOT)}: needs a non-empty string '{field}' (data/README.md)")
                    failures += 1
            validated += 1
    covered = {str(ROOT / f) for f in SCHEMA_OF_FOLDER}
    for path in sorted((ROOT / "data").rglob("*.json")):
        if str(path.parent) not in covered:
            print(f"FAIL {path.relative_to(ROOT)}: no schema is assigned to its folder (scripts/check_docs.py)")
            failures += 1
    for name, doc, what in ACCEPTED:
        if errors(name, doc):
            print(f"FAIL {name} rejects a valid document ({what}): {errors(name, doc)[0].message[:200]}")
            failures += 1
    for name, doc, what in REJECTED:
        if not errors(name, doc):
            print(f"FAIL {name} accepts a broken document ({what})")
            failures += 1
    print(f"schemas: {len(schemas)} schemas, {validated} data files validated, {len(ACCEPTED)} valid and "
          f"{len(REJECTED)} broken documents tried, {failures} failures")
    return 1 if failures or validated == 0 else 0


# ---- links --------------------------------------------------------------------------------------

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def strip_fences(text):
    return re.sub(r"^(```|~~~).*?^\1", "", text, flags=re.S | re.M)


def strip_code(text):
    """Markdown without fenced code blocks and inline code spans (links there are not links)."""
    return re.sub(r"`[^`\n]*`", "", strip_fences(text))


def anchors_of(path, cache={}):
    """GitHub-style anchors of a Markdown file's headings."""
    if path not in cache:
        found = set()
        counts = {}
        for line in strip_fences(path.read_text(encoding="utf-8")).splitlines():
            m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
            if not m:
                continue
            slug = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", m.group(1)).strip().lower()
            slug = re.sub(r"[^\w\- ]", "", slug, flags=re.U).replace(" ", "-")
            n = counts.get(slug, 0)
            counts[slug] = n + 1
            found.add(slug if n == 0 else f"{slug}-{n}")
        cache[path] = found
    return cache[path]


def check_links():
    failures = checked = 0
    files = tracked_files(r"\.md$")
    for md in files:
        text = strip_code(md.read_text(encoding="utf-8"))
        for target in LINK.findall(text):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
                continue
            checked += 1
            file_part, _, anchor = target.partition("#")
            dest = md if not file_part else (md.parent / file_part).resolve()
            where = md.relative_to(ROOT)
            if not dest.exists():
                print(f"FAIL {where}: link '{target}': {file_part} does not exist")
                failures += 1
            elif ROOT not in dest.parents and dest != ROOT:
                print(f"FAIL {where}: link '{target}' leaves the repository")
                failures += 1
            elif anchor and dest.suffix == ".md" and anchor not in anchors_of(dest):
                print(f"FAIL {where}: link '{target}': no heading #{anchor} in {dest.relative_to(ROOT)}")
                failures += 1
    print(f"links: {checked} relative links in {len(files)} Markdown files, {failures} broken")
    return 1 if failures or not files else 0


# ---- selfcontained ------------------------------------------------------------------------------

OUTSIDE = [
    (re.compile(r"\.\./shared"), "a path outside the repository"),
    (re.compile(r"seeds/0\d\d_"), "a lecture-note file outside the repository (cite LN0..LN4, docs/references.md)"),
    (re.compile(r"(?<![\w/.\[])(?:math|formats)\.md\s*(?:§|section)"), "a bare document name (write docs/math.md §N)"),
    (re.compile(r"solver-notes\.md"), "a document outside the repository (docs/solvers.md)"),
]


def check_selfcontained():
    failures = 0
    files = [f for f in tracked_files() if f.suffix in {".md", ".json", ".sh", ".py", ".txt", ".h", ".cpp", ".cmake"}
             or f.name == "CMakeLists.txt"]
    me = Path(__file__).resolve()
    for f in files:
        if f.resolve() == me:
            continue
        try:
            text = f.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            for pattern, why in OUTSIDE:
                if pattern.search(line):
                    print(f"FAIL {f.relative_to(ROOT)}:{number}: {why}: {line.strip()[:120]}")
                    failures += 1
    print(f"selfcontained: {len(files)} files, {failures} references outside the repository")
    return 1 if failures else 0


# ---- reference ----------------------------------------------------------------------------------
# The reference numbers of data/reference/ recomputed with nothing but the definitions: the mask
# equations solved by Gaussian elimination, Bernstein polynomials, Gauss-Legendre quadrature.

def gauss_legendre(k):
    nodes = []
    for i in range(1, k + 1):
        x = math.cos(math.pi * (i - 0.25) / (k + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for n in range(2, k + 1):
                p0, p1 = p1, ((2 * n - 1) * x * p1 - (n - 1) * p0) / n
            dp = k * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        nodes.append(((x + 1) / 2, 1 / ((1 - x * x) * dp * dp)))  # on [0, 1]: weight 2/((1-x²)P'²) / 2
    return nodes


def bernstein(n, i, t, d=0):
    """d-th derivative of B_i^n at t."""
    if d == 0:
        return math.comb(n, i) * t ** i * (1 - t) ** (n - i) if 0 <= i <= n else 0.0
    if n == 0:
        return 0.0
    return n * (bernstein(n - 1, i - 1, t, d - 1) - bernstein(n - 1, i, t, d - 1))


def surface_partial(net, u, v, a, b):
    m, n = len(net) - 1, len(net[0]) - 1
    out = [0.0, 0.0, 0.0]
    for i in range(m + 1):
        bu = bernstein(m, i, u, a)
        if bu == 0:
            continue
        for j in range(n + 1):
            w = bu * bernstein(n, j, v, b)
            for c in range(3):
                out[c] += w * net[i][j][c]
    return out


def energy(net, terms, k=12):
    """∫∫ Σ weight·‖∂^a_u ∂^b_v p‖² over [0,1]², by Gauss-Legendre (exact for these degrees)."""
    total = 0.0
    for u, wu in gauss_legendre(k):
        for v, wv in gauss_legendre(k):
            for (a, b), weight in terms.items():
                d = surface_partial(net, u, v, a, b)
                total += wu * wv * weight * sum(x * x for x in d)
    return total


THIN_PLATE = {(2, 0): 1, (1, 1): 2, (0, 2): 1}
DIRICHLET = {(1, 0): 1, (0, 1): 1}
TWIST = {(1, 1): 1}


def mask_net(boundary, alpha):
    """The net whose interior satisfies b_ij = α·(diagonal sum) + (1/4 − α)·(edge sum)."""
    m, n = len(boundary["bottom"]) - 1, len(boundary["left"]) - 1
    net = [[None] * (n + 1) for _ in range(m + 1)]
    for i in range(m + 1):
        net[i][0], net[i][n] = boundary["bottom"][i], boundary["top"][i]
    for j in range(n + 1):
        net[0][j], net[m][j] = boundary["left"][j], boundary["right"][j]
    unknowns = [(i, j) for i in range(1, m) for j in range(1, n)]
    index = {p: k for k, p in enumerate(unknowns)}
    size = len(unknowns)
    A = [[0.0] * size for _ in range(size)]
    B = [[0.0] * 3 for _ in range(size)]
    beta = 0.25 - alpha
    for k, (i, j) in enumerate(unknowns):
        A[k][k] = 1.0
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                if di == dj == 0:
                    continue
                w = alpha if di and dj else beta
                q = (i + di, j + dj)
                if q in index:
                    A[k][index[q]] -= w
                else:
                    for c in range(3):
                        B[k][c] += w * net[q[0]][q[1]][c]
    for col in range(size):  # Gaussian elimination with partial pivoting
        piv = max(range(col, size), key=lambda r: abs(A[r][col]))
        A[col], A[piv], B[col], B[piv] = A[piv], A[col], B[piv], B[col]
        for r in range(size):
            if r != col and A[r][col] != 0:
                f = A[r][col] / A[col][col]
                A[r] = [x - f * y for x, y in zip(A[r], A[col])]
                B[r] = [x - f * y for x, y in zip(B[r], B[col])]
    for k, (i, j) in enumerate(unknowns):
        net[i][j] = [B[k][c] / A[k][k] for c in range(3)]
    return net


def rms_to_sphere(net, center, radius, samples):
    total = 0.0
    for a in range(samples):
        for b in range(samples):
            p = surface_partial(net, a / (samples - 1), b / (samples - 1), 0, 0)
            total += (math.dist(p, center) - radius) ** 2
    return math.sqrt(total / samples ** 2)


def compare(label, computed, stored, failures):
    value, decimals = stored["value"], stored["decimals"]
    ok = abs(computed - value) <= 0.5 * 10.0 ** -decimals * (1 + 1e-9)
    print(f"{'ok  ' if ok else 'FAIL'} {label}: computed {computed:.{decimals + 3}f}, stored {value} ({decimals} decimals)")
    return failures + (not ok)


def check_reference():
    failures = 0
    folder = ROOT / "data" / "reference"
    tables = sorted(folder.glob("*.json"))
    for path in tables:
        ref = json.loads(path.read_text())
        boundary = json.loads((ROOT / ref["boundary_file"]).read_text())
        for row in ref["rows"]:
            net = mask_net(boundary, row["alpha"])
            label = f"{path.name} alpha = {row['alpha']}"
            for key, stored in row.items():
                if key == "alpha":
                    continue
                if key == "centre_z":
                    computed = surface_partial(net, 0.5, 0.5, 0, 0)[2]
                elif key == "interior_point":
                    for c, s in enumerate(stored):
                        failures = compare(f"{label} interior b[1][1][{c}]", net[1][1][c], s, failures)
                    continue
                elif key == "thin_plate":
                    computed = energy(net, THIN_PLATE)
                elif key == "dirichlet":
                    computed = energy(net, DIRICHLET)
                elif key == "twist":
                    computed = energy(net, TWIST)
                elif key == "rms_to_target":
                    t = boundary["target"]["sphere"]
                    computed = rms_to_sphere(net, t["center"], t["radius"], ref["rms_samples"])
                else:
                    print(f"FAIL {path.name}: unknown column '{key}'")
                    failures += 1
                    continue
                failures = compare(f"{label} {key}", computed, stored, failures)
    print(f"reference: {len(tables)} tables, {failures} numbers that do not follow from first principles")
    return 1 if failures or not tables else 0


# ---- tests --------------------------------------------------------------------------------------

CITING = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "docs").glob("*.md")) + ["README.md", "data/README.md"]


def check_tests():
    """A backticked "function: property" in the documents that cite tests names a TEST_CASE."""
    names = set()
    for f in (ROOT / "tests").rglob("*.cpp"):
        # a name may be written as adjacent literals, which C++ joins
        for literals in re.findall(r'TEST_CASE\(\s*((?:"(?:[^"\\]|\\.)*"\s*)+)', f.read_text(encoding="utf-8")):
            names.add("".join(re.findall(r'"((?:[^"\\]|\\.)*)"', literals)))
    heads = {name.split(": ", 1)[0] for name in names}
    failures = cited = 0
    for doc in CITING:
        text = (ROOT / doc).read_text(encoding="utf-8")
        text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)  # fenced blocks: no citations
        # a code span may run over line breaks within its paragraph (Markdown reads each as a
        # space); backticks pair within a paragraph, never across a blank line
        spans = []
        for paragraph in re.split(r"\n\s*\n", text):
            spans += re.findall(r"`([^`]+)`", re.sub(r"\s*\n\s*", " ", paragraph))
        for span in spans:
            # a citation names what a test is about (its head, "function: …") and then the property;
            # a span whose head no test has is a message or a field ("breakdown: residual R …",
            # "free[i][j]: …"), and one with a placeholder ("…") is a pattern
            if ": " not in span or "…" in span or span.split(": ", 1)[0] not in heads:
                continue
            cited += 1
            if span not in names:
                print(f"FAIL {doc}: cites `{span}`, which is no TEST_CASE in tests/")
                failures += 1
    print(f"tests: {cited} test names cited in {len(CITING)} documents, {len(names)} TEST_CASEs, {failures} missing")
    return 1 if failures or not cited else 0


CHECKS = {"schemas": check_schemas, "links": check_links, "selfcontained": check_selfcontained,
          "reference": check_reference, "tests": check_tests}


def main(argv):
    names = argv[1:] or ["all"]
    if names == ["all"]:
        names = list(CHECKS)
    unknown = [n for n in names if n not in CHECKS]
    if unknown:
        print(f"usage: check_docs.py [{'|'.join(CHECKS)}|all] (unknown: {', '.join(unknown)})", file=sys.stderr)
        return 2
    return max(CHECKS[n]() for n in names)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
