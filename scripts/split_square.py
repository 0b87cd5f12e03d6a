#!/usr/bin/env python3
"""The unit square split along its diagonal (E05, "rectangle against triangle"): boundary files of
the same known surface s(u, v) for the rectangular and the triangular problem, and the evaluation of
the nets coons returns on the lower-left triangle T = {u, v >= 0, u + v <= 1}. Python 3 standard
library only; run alone it writes the files of one shape and degree and prints the fit errors:

    python3 scripts/split_square.py dome 6 OUT_DIR

Rectangle: the sides s(t, 0), s(t, 1), s(0, t), s(1, t), each the least-squares Bézier fit of
degree n (end points interpolated; scripts/make_triangles.py's fit_bezier). Triangle: corners
A = s(0, 0) = b[n][0][0], B = s(1, 0) = b[0][n][0], C = s(0, 1) = b[0][0][n]; sides[0] = s(t, 0)
(the rectangle's bottom, the same points), sides[1] = the diagonal s(1 − t, t), sides[2] =
s(0, 1 − t) (the rectangle's left, reversed). A point (u, v) of T has barycentric coordinates
(1 − u − v, u, v) for (A, B, C), so both nets are evaluated at the same parameters."""
import json
import math
import pathlib
import sys
from math import comb, factorial

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from make_triangles import fit_bezier  # noqa: E402


def dome(u, v):
    """The sphere of radius √3 about (0, 0, −1) over [−1, 1]² (data/boundaries/dome.json)."""
    x, y = 2 * u - 1, 2 * v - 1
    return [x, y, math.sqrt(3 - x * x - y * y) - 1]


def monkey_saddle(u, v):
    """z = (x³ − 3xy²)/2 over [−1, 1]² (the surface of data/triangles/monkey_saddle.json)."""
    x, y = 2 * u - 1, 2 * v - 1
    return [x, y, (x**3 - 3 * x * y * y) / 2]


SURFACES = {"dome": dome, "monkey_saddle": monkey_saddle}


def gap(shape, p):
    """The distance of a point from the surface: from the sphere for the dome, vertical for the graph."""
    if shape == "dome":
        return abs(math.dist(p, [0.0, 0.0, -1.0]) - math.sqrt(3))
    x, y, z = p
    return abs(z - (x**3 - 3 * x * y * y) / 2)


def boundaries(shape, n):
    """(rectangle boundary dict, triangle boundary dict, {side: max fit error})."""
    s = SURFACES[shape]
    fits = {
        "bottom": fit_bezier(lambda t: s(t, 0.0), n),
        "top": fit_bezier(lambda t: s(t, 1.0), n),
        "left": fit_bezier(lambda t: s(0.0, t), n),
        "right": fit_bezier(lambda t: s(1.0, t), n),
        "diagonal": fit_bezier(lambda t: s(1 - t, t), n),
    }
    rect = {"name": f"{shape}-square-{n}", "degree": [n, n]}
    for side in ("bottom", "top", "left", "right"):
        rect[side] = fits[side][0]
    left = fits["left"][0]
    tri = {"name": f"{shape}-half-{n}", "type": "triangle", "degree": n,
           "sides": [fits["bottom"][0], fits["diagonal"][0], list(reversed(left))]}
    return rect, tri, {side: fit[1] for side, fit in fits.items()}


def triangle_points(N):
    """Centroids of the N² congruent sub-triangles of T and the weight area/N² of each."""
    pts = []
    for a in range(N):
        for b in range(N - a):
            pts.append(((a + 1 / 3) / N, (b + 1 / 3) / N))
            if a + b < N - 1:
                pts.append(((a + 2 / 3) / N, (b + 2 / 3) / N))
    return pts, 0.5 / (N * N)


def bern(n, i, t):
    return comb(n, i) * t**i * (1 - t) ** (n - i)


def rect_basis(n, u, v):
    bu = [bern(n, i, u) for i in range(n + 1)]
    bv = [bern(n, j, v) for j in range(n + 1)]
    return [bu[i] * bv[j] for i in range(n + 1) for j in range(n + 1)]


def tri_basis(n, u, v):
    """Weights of b[n−k−j][j][k] in the order of the report's net rows (k, then j)."""
    w = 1 - u - v
    return [factorial(n) / (factorial(n - k - j) * factorial(j) * factorial(k)) * w ** (n - k - j) * u**j * v**k
            for k in range(n + 1) for j in range(n + 1 - k)]


H = 1e-3  # central second differences of the basis (truncation ~H², rounding ~1e-16/H²)


class Sampler:
    """Precomputed basis weights at the quadrature points of T for one family and degree."""

    def __init__(self, family, n, N=40):
        basis = rect_basis if family == "rectangle" else tri_basis
        self.points, self.weight = triangle_points(N)
        self.values, self.second = [], []
        for u, v in self.points:
            f = {(a, b): basis(n, u + a * H, v + b * H) for a in (-1, 0, 1) for b in (-1, 0, 1)}
            c = f[(0, 0)]
            uu = [(f[(1, 0)][q] - 2 * c[q] + f[(-1, 0)][q]) / H**2 for q in range(len(c))]
            vv = [(f[(0, 1)][q] - 2 * c[q] + f[(0, -1)][q]) / H**2 for q in range(len(c))]
            uv = [(f[(1, 1)][q] - f[(1, -1)][q] - f[(-1, 1)][q] + f[(-1, -1)][q]) / (4 * H * H) for q in range(len(c))]
            self.values.append(c)
            self.second.append((uu, uv, vv))

    @staticmethod
    def flat(net):
        return [p for row in net for p in row]

    @staticmethod
    def combine(weights, pts):
        return [sum(w * p[c] for w, p in zip(weights, pts)) for c in range(3)]

    def distance(self, net, shape):
        """(RMS over T, max at the points) of the distance of net(u, v) from the surface (gap())."""
        pts = self.flat(net)
        sq, worst = 0.0, 0.0
        for w in self.values:
            d = gap(shape, self.combine(w, pts))
            sq += d * d
            worst = max(worst, d)
        return math.sqrt(sq / len(self.points)), worst

    def thin_plate(self, net):
        """∫_T |F_uu|² + 2|F_uv|² + |F_vv|² du dv (centroid rule)."""
        pts = self.flat(net)
        total = 0.0
        for uu, uv, vv in self.second:
            a, b, c = self.combine(uu, pts), self.combine(uv, pts), self.combine(vv, pts)
            total += sum(x * x for x in a) + 2 * sum(x * x for x in b) + sum(x * x for x in c)
        return total * self.weight


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in SURFACES:
        raise SystemExit(f"usage: split_square.py {{{'|'.join(SURFACES)}}} DEGREE OUT_DIR")
    shape, n, out = sys.argv[1], int(sys.argv[2]), pathlib.Path(sys.argv[3])
    rect, tri, errors = boundaries(shape, n)
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{rect['name']}.json").write_text(json.dumps(rect))
    (out / f"{tri['name']}.json").write_text(json.dumps(tri))
    for side, e in errors.items():
        print(f"{side}: max fit error {e:.3e}")


if __name__ == "__main__":
    main()
