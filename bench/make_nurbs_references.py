#!/usr/bin/env python3
"""NURBS reference data from geomdl (NURBS-Python) for crates/splinekit/tests/nurbs_geomdl.rs.

Writes crates/splinekit/tests/data/nurbs/geomdl.json: seeded random NURBS curves (degrees 1 to 5
and 7, 2D and 3D, clamped uniform, clamped non-uniform with repeated interior knots, one
unclamped knot vector, one domain away from 0, weights in [0.2, 5]) with, for each, geomdl's
points, first and second derivatives at knot-vector parameters x (the domain's ends, every
interior knot, random values), and geomdl's knot insertion (operations.insert_knot: once at a
random x, once at an existing interior knot, twice at a random x): the new knots, control
points (unweighted) and weights.

Conventions checked here before writing: the curve is given to geomdl by its weighted control
points (x·w, y·w, [z·w,] w) through `ctrlptsw`, its knot vector unnormalized
(`normalize_kv=False`, the default would rescale it to [0, 1]); `derivatives(x, order)` returns
derivatives of the rational curve C(x) itself (Algorithm A4.2, not of the homogeneous curve),
with respect to x; geomdl finds the span of x with knots[k] <= x < knots[k+1], the last span
at the domain's end. The script checks that geomdl's first derivative agrees with a central
difference of its points, and that each knot insertion leaves the curve's points unchanged.

Numbers are written by json (shortest round-trip repr), so Rust parses the same doubles; one
line per evaluation and per insertion.
Deterministic: the same geomdl version writes the same file. Not for CI (the data is
committed). Needs geomdl, pinned in bench/requirements.txt (pure Python, no other package):

    bench/install_peers.sh && bench/.venv/bin/python bench/make_nurbs_references.py
or, without the other peers:
    python3 -m venv /tmp/geomdl-venv && /tmp/geomdl-venv/bin/pip install geomdl==5.4.0
    /tmp/geomdl-venv/bin/python bench/make_nurbs_references.py
"""

import json
import os
import random
import sys
from pathlib import Path

if os.environ.get("CI") == "true":
    print("make_nurbs_references.py: not for CI", file=sys.stderr)
    sys.exit(0)

import geomdl  # noqa: E402
from geomdl import NURBS, operations  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "crates/splinekit/tests/data/nurbs/geomdl.json"
SEED = 0x41  # issue #41

# (degree, dimension, control points, knot vector kind); named p{degree}_{dimension}d_{kind}
CASES = [
    (1, 2, 5, "uniform"),
    (1, 3, 7, "nonuniform"),
    (2, 2, 6, "uniform"),
    (2, 3, 8, "repeated"),
    (2, 2, 7, "offset"),
    (3, 2, 7, "uniform"),
    (3, 3, 10, "repeated"),
    (3, 2, 8, "unclamped"),
    (4, 2, 9, "nonuniform"),
    (4, 3, 8, "uniform"),
    (5, 2, 14, "repeated"),
    (5, 3, 9, "uniform"),
    (7, 3, 18, "repeated"),
]
RANDOM_PARAMS = 8


def knot_vector(rng, kind, degree, n):
    """`n + degree + 1` non-decreasing knots of the given kind."""
    spans = n - degree
    if kind == "uniform":
        interior = [float(i) for i in range(1, spans)]
        return [0.0] * (degree + 1) + interior + [float(spans)] * (degree + 1)
    if kind == "unclamped":
        return sorted(rng.uniform(0.0, 10.0) for _ in range(n + degree + 1))
    count = spans - 1
    if kind == "repeated":
        # one interior knot of multiplicity `degree` (C0 there) and one of multiplicity 2
        # (both capped by the degree), among `distinct` random values
        full, double = degree, min(2, degree)
        distinct = count - full - double + 2
        assert distinct >= 2, "too few control points for the repeated knots"
        values = sorted(rng.uniform(0.0, 1.0) for _ in range(distinct))
        interior = sorted(values + [values[distinct // 3]] * (full - 1) + [values[2 * distinct // 3]] * (double - 1))
    else:
        interior = sorted(rng.uniform(0.0, 1.0) for _ in range(count))
    lo, hi = (2.5, 9.0) if kind == "offset" else (0.0, 1.0)
    interior = [lo + (hi - lo) * k for k in interior]
    return [lo] * (degree + 1) + interior + [hi] * (degree + 1)


def make_curve(degree, points, weights, knots):
    curve = NURBS.Curve(normalize_kv=False)
    curve.degree = degree
    curve.ctrlptsw = [[c * w for c in p] + [w] for p, w in zip(points, weights)]
    curve.knotvector = knots
    return curve


def domain(curve):
    n = len(curve.ctrlptsw)
    return curve.knotvector[curve.degree], curve.knotvector[n]


def params(rng, curve):
    """The domain's ends, every distinct knot inside it and random values, ascending."""
    a, b = domain(curve)
    xs = {k for k in curve.knotvector if a <= k <= b}
    xs.update(rng.uniform(a, b) for _ in range(RANDOM_PARAMS))
    return sorted(xs)


def scale(points):
    return max(max(abs(c) for c in p) for p in points)


def check_derivative(curve, x, d1):
    """geomdl's first derivative against a difference of its points inside the span geomdl
    uses at x (knots[k] <= x < knots[k + 1], the last span at the end): central where the
    span allows it, else one-sided."""
    knots, n = curve.knotvector, len(curve.ctrlptsw)
    k = max(s for s in range(curve.degree, n) if knots[s] <= x and knots[s] < knots[s + 1])
    h = 1e-6 * (knots[k + 1] - knots[k])
    lo, hi = max(knots[k], x - h), min(knots[k + 1], x + h)
    p_lo, p_hi = curve.evaluate_single(lo), curve.evaluate_single(hi)
    fd = [(q - p) / (hi - lo) for p, q in zip(p_lo, p_hi)]
    err = max(abs(f - d) for f, d in zip(fd, d1))
    # O(h) one-sided, O(h²) central: a loose bound, meant to catch a wrong convention
    assert err <= 1e-4 * max(abs(d) for d in d1), (x, fd, d1, err)


def insertion(curve, x, times):
    new = make_curve(curve.degree, curve.ctrlpts, curve.weights, list(curve.knotvector))
    operations.insert_knot(new, [x], [times])
    return new


def flat(value):
    return not isinstance(value, (dict, list)) or (
        isinstance(value, list) and all(not isinstance(v, dict) for v in value)
    )


def layout(value, depth=0):
    """JSON with one line per evaluation, per insertion and per field of a curve, so that a
    regenerated file diffs readably; numbers as json writes them (shortest round-trip)."""
    compact = json.dumps(value, separators=(",", ":"))
    if flat(value) or (isinstance(value, dict) and all(flat(v) for v in value.values())):
        return compact
    pad, inner = " " * depth, " " * (depth + 1)
    if isinstance(value, list):
        return "[\n" + ",\n".join(inner + layout(v, depth + 1) for v in value) + "\n" + pad + "]"
    items = (inner + json.dumps(k) + ":" + layout(v, depth + 1) for k, v in value.items())
    return "{\n" + ",\n".join(items) + "\n" + pad + "}"


def main():
    rng = random.Random(SEED)
    curves = []
    for degree, dim, n, kind in CASES:
        name = f"p{degree}_{dim}d_{kind}"
        points = [[rng.uniform(-10.0, 10.0) for _ in range(dim)] for _ in range(n)]
        weights = [rng.uniform(0.2, 5.0) for _ in range(n)]
        knots = knot_vector(rng, kind, degree, n)
        curve = make_curve(degree, points, weights, knots)
        size = scale(points)
        # round trip: geomdl's unweighted points and weights are the ones given
        assert all(abs(a - b) <= 1e-15 * size for p, q in zip(curve.ctrlpts, points) for a, b in zip(p, q))
        assert all(abs(a - b) <= 1e-15 * 5 for a, b in zip(curve.weights, weights))
        evals = []
        for x in params(rng, curve):
            d = curve.derivatives(x, order=2)
            check_derivative(curve, x, d[1])
            evals.append({"x": x, "point": d[0], "d1": d[1], "d2": d[2]})
        a, b = domain(curve)
        interior = sorted({k for k in knots if a < k < b and knots.count(k) < degree})
        inserts = [(rng.uniform(a, b), 1)]
        if interior:
            inserts.append((interior[len(interior) // 2], 1))
        if degree >= 2:
            inserts.append((rng.uniform(a, b), 2))
        insertions = []
        for x, times in inserts:
            new = insertion(curve, x, times)
            for e in evals:
                moved = max(abs(p - q) for p, q in zip(new.evaluate_single(e["x"]), e["point"]))
                assert moved <= 1e-12 * size, (name, x, e["x"], moved)
            insertions.append(
                {"x": x, "times": times, "knots": new.knotvector, "points": new.ctrlpts, "weights": new.weights}
            )
        curves.append(
            {
                "name": name,
                "degree": degree,
                "knots": knots,
                "points": points,
                "weights": weights,
                "evals": evals,
                "insertions": insertions,
            }
        )
    data = {
        "source": f"geomdl {geomdl.__version__} (bench/make_nurbs_references.py, seed {SEED})",
        "curves": curves,
    }
    OUT.parent.mkdir(parents=True, exist_ok=True)
    with open(OUT, "w") as f:
        f.write(layout(data) + "\n")
    print(f"{OUT.relative_to(ROOT)}: {len(curves)} curves, {OUT.stat().st_size} bytes", file=sys.stderr)


if __name__ == "__main__":
    main()
