#!/usr/bin/env python3
"""Compares two triangle meshes whose vertices are numbered differently (needs numpy and
scipy: run it with the venv's python, bench/.venv/bin/python).

    compare_meshes.py A.obj B.obj [--tol 1e-12] [--boundary-only]

Matches every vertex of A to the nearest vertex of B, then reports: the largest distance of a
match, whether the matching is a bijection, whether A's triangles mapped through it are B's
triangles (same orientation, up to rotation of the corners), and how many vertices are
farther apart than --tol (relative to the bounding-box diagonal of B). Exit status 0 when the
meshes agree to --tol, 1 otherwise.

--boundary-only compares only the vertices on the boundary of each mesh (those of a boundary
edge): under the crease rules their positions depend on boundary vertices alone, so two
schemes that differ only in the interior weights (Loop's beta and Warren's) must still agree
there.
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

sys.dont_write_bytecode = True  # no __pycache__ in bench/
sys.path.insert(0, str(Path(__file__).resolve().parent))
from meshgen import read_obj  # noqa: E402


def canon(t):
    k = t.index(min(t))
    return t[k:] + t[:k]


def boundary_vertices(faces):
    half = {(t[k], t[(k + 1) % 3]) for t in faces for k in range(3)}
    return sorted({v for (x, y) in half if (y, x) not in half for v in (x, y)})


def compare_boundary(a_path, b_path, tol):
    pa, fa = read_obj(a_path)
    pb, fb = read_obj(b_path)
    a = np.array(pa)[boundary_vertices(fa)]
    b = np.array(pb)[boundary_vertices(fb)]
    if len(a) == 0 or len(a) != len(b):
        return False, f"boundary vertex counts differ or are zero: {len(a)} against {len(b)}"
    scale = float(np.linalg.norm(b.max(axis=0) - b.min(axis=0))) or 1.0
    dist, idx = cKDTree(b).query(a)
    bij = len(set(idx.tolist())) == len(b)
    far = int((dist / scale > tol).sum())
    return bij and far == 0, f"{len(a)} boundary vertices, max|d|={dist.max():.3g} bijection={bij} beyond_tol={far}"


def compare(a_path, b_path, tol):
    pa, fa = read_obj(a_path)
    pb, fb = read_obj(b_path)
    a, b = np.array(pa), np.array(pb)
    scale = float(np.linalg.norm(b.max(axis=0) - b.min(axis=0))) or 1.0
    if len(a) != len(b) or len(fa) != len(fb):
        return False, f"counts differ: {len(a)} v {len(fa)} f against {len(b)} v {len(fb)} f"
    dist, idx = cKDTree(b).query(a)
    bij = len(set(idx.tolist())) == len(b)
    fb_set = {canon(tuple(t)) for t in fb}
    mapped = {canon(tuple(int(idx[v]) for v in t)) for t in fa}
    same_faces = mapped == fb_set
    rel = dist / scale
    far = int((rel > tol).sum())
    ok = bij and same_faces and far == 0
    worst = int(np.argmax(dist))
    msg = (f"V={len(a)} F={len(fa)} max|d|={dist.max():.3g} (rel {rel.max():.3g}, at A vertex {worst} "
           f"{a[worst].tolist()}) bijection={bij} same_triangles={same_faces} beyond_tol={far}")
    return ok, msg


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--tol", type=float, default=1e-12)
    ap.add_argument("--boundary-only", action="store_true")
    args = ap.parse_args()
    ok, msg = (compare_boundary if args.boundary_only else compare)(args.a, args.b, args.tol)
    print(("agree: " if ok else "DIFFER: ") + msg)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
