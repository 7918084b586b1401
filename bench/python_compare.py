"""splinekit's Python package against Python peers (issue #43):

- Loop subdivision, one level of a 100 352-triangle torus: splinekit.subdivide vs
  trimesh.remesh.subdivide_loop and open3d's TriangleMesh.subdivide_loop;
- arc length of 10 000 random cubic Béziers to 1e-9: splinekit's Curve.arclen vs
  scipy.integrate.quad of the speed |P'(t)| (a Python loop over the curves in both).

    python bench/python_compare.py          # peers that are not installed are skipped

The peers: `pip install trimesh scipy open3d-cpu` (open3d also needs Debian's libusb-1.0-0).

Prints the median of 5 runs (3 for the slow ones) and the ratio to splinekit.
"""

import statistics
import time

import numpy as np

import splinekit as sk


def median_time(fn, runs=5):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def torus(n=224, m=224, R=1.0, r=0.3):
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    u, v = 2 * np.pi * i / n, 2 * np.pi * j / m
    verts = np.stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)], -1).reshape(-1, 3)
    a = (i * m + j).ravel()
    b = (((i + 1) % n) * m + j).ravel()
    c = (((i + 1) % n) * m + (j + 1) % m).ravel()
    d = (i * m + (j + 1) % m).ravel()
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return verts, faces


def report(title, rows):
    print(f"\n{title}")
    base = rows[0][1]
    for name, t in rows:
        print(f"  {name:<34} {t * 1e3:10.1f} ms   {t / base:7.1f}x")


def loop_subdivision():
    v, f = torus()
    rows = [("splinekit.subdivide (loop)", median_time(lambda: sk.subdivide(v, f, 1)))]
    try:
        import trimesh.remesh

        rows.append(("trimesh.remesh.subdivide_loop", median_time(lambda: trimesh.remesh.subdivide_loop(v, f, 1), 3)))
    except ImportError:
        print("(trimesh not installed)")
    try:
        import open3d as o3d

        mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(f.astype(np.int32)))
        rows.append(("open3d subdivide_loop", median_time(lambda: mesh.subdivide_loop(1), 3)))
        # the same mesh: counts, and the vertices (open3d numbers them as splinekit does not,
        # so compare the sorted coordinates)
        theirs, (mv, mf) = mesh.subdivide_loop(1), sk.subdivide(v, f, 1)
        tv = np.asarray(theirs.vertices)
        assert (len(tv), len(theirs.triangles)) == (len(mv), len(mf)), (len(tv), len(mv))
        gap = np.abs(np.sort(tv, axis=0) - np.sort(mv, axis=0)).max()
        print(f"open3d vs splinekit: {len(mv)} vertices, {len(mf)} triangles each; sorted coordinates differ by {gap:.1e}")
    except ImportError:
        print("(open3d not installed)")
    report(f"Loop subdivision, 1 level of {len(f)} triangles", rows)


def arc_lengths():
    rng = np.random.default_rng(43)
    cubics = rng.uniform(-1, 1, (10_000, 4, 2))
    rows = [("splinekit Curve.arclen(1e-9)", median_time(lambda: [sk.Curve.bezier(p).arclen(1e-9) for p in cubics], 3))]
    try:
        from scipy.integrate import quad

        def speed(t, p):
            s = 1 - t
            d = 3 * s * s * (p[1] - p[0]) + 6 * s * t * (p[2] - p[1]) + 3 * t * t * (p[3] - p[2])
            return np.hypot(d[0], d[1])

        mine = np.array([sk.Curve.bezier(p).arclen(1e-12) for p in cubics[:200]])
        theirs = np.array([quad(speed, 0, 1, args=(p,), epsabs=1e-9, epsrel=0, limit=200)[0] for p in cubics[:200]])
        print(f"\nscipy quad vs splinekit (1e-12) on 200 cubics: largest difference {np.max(np.abs(mine - theirs)):.1e}")
        rows.append(
            ("scipy.integrate.quad (epsabs 1e-9)", median_time(lambda: [quad(speed, 0, 1, args=(p,), epsabs=1e-9, epsrel=0, limit=200) for p in cubics], 3))
        )
    except ImportError:
        print("(scipy not installed)")
    report("Arc length of 10 000 cubic Béziers", rows)


if __name__ == "__main__":
    loop_subdivision()
    arc_lengths()
