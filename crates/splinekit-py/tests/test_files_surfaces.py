"""Files, sweeps, revolutions and subdivision: counts, round trips, references, and trimesh."""

import numpy as np
import pytest

import splinekit as sk


def test_read_swp_curves_and_surfaces(repo):
    doc = sk.read_swp(repo / "examples" / "trefoil-knot.swp")
    assert list(doc.curves) == ["ellipse", "knot", "spin"]
    (name, surface), = doc.surfaces.items()
    assert surface.kind == "gcyl" and surface.curves == ["ellipse", "knot", "spin"]
    v, f = surface.mesh()
    assert v.dtype == np.float64 and f.dtype == np.int64 and v.shape[1] == 3 and f.shape[1] == 3
    assert f.min() >= 0 and f.max() < len(v)
    v2, f2, n2 = surface.mesh(normals=True)
    assert n2.shape == v2.shape


@pytest.mark.parametrize(
    "name, triangles",
    [("srev/norm.swp", 9000), ("gcyl/gentorus.swp", 6400), ("gcyl/florus.swp", 15000), ("gcyl/tor.swp", 3600), ("gcyl/weird.swp", 16384)],
)
def test_course_files_triangle_counts(repo, name, triangles):
    path = repo / "crates" / "splinekit-io" / "tests" / "data" / "swp" / name
    if not path.exists():
        pytest.skip(f"{path} not in this checkout")
    (surface,) = sk.read_swp(path).surfaces.values()
    v, f = surface.mesh()
    assert len(f) == triangles


def test_revolve_counts_and_orientation():
    profile = sk.Curve.bspline([[-1.0, 0.0], [-1.0, 1.0], [-0.5, 2.0], [-0.2, 3.0]], steps=10)
    v, f = sk.revolve(profile, slices=16)
    assert v.shape == (11 * 16, 3) and f.shape == (10 * 16 * 2, 3)
    # every vertex at its profile point's distance from the y axis
    u, p = profile.flatten()
    radii = np.sort(np.unique(np.round(np.hypot(v[:, 0], v[:, 2]), 12)))
    np.testing.assert_allclose(radii, np.sort(np.unique(np.round(np.abs(p[:, 0]), 12))), atol=1e-12)
    # outward: the face normals point away from the axis
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    normal = np.cross(b - a, c - a)
    centre = (a + b + c) / 3
    radial = centre * [1, 0, 1]
    assert np.all(np.einsum("ij,ij->i", normal, radial) > 0)


def tube():
    knot = sk.Curve.trefoil(1.0)
    ring = sk.Curve.circle(0.15)
    return sk.sweep(ring, knot, tolerance=1e-3)


def test_closed_sweep_is_a_closed_manifold():
    v, f = tube()
    edges = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2)
    # Euler characteristic of a torus
    assert len(v) - len(counts) + len(f) == 0


def test_trimesh_round_trip(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    v, f = tube()
    mesh = trimesh.Trimesh(v, f, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume > 0  # outward normals
    # an open path with a closed profile gets caps on the tube's own vertices: a solid too,
    # as given (nothing merged)
    line = sk.Curve.bezier([[0, 0, 0], [0, 0, 1], [0, 1, 2], [0, 1, 3]])
    sv, sf = sk.sweep(sk.Curve.circle(0.2), line, caps=True)
    closed = trimesh.Trimesh(sv, sf, process=False)
    assert closed.is_watertight and closed.is_winding_consistent
    assert closed.volume > 0
    # a square profile (creases) along an L (a mitred corner), capped
    square = sk.Curve.bezier([[-0.2, -0.2], [0, -0.2], [0, -0.2], [0.2, -0.2], [0.2, 0], [0.2, 0], [0.2, 0.2],
                              [0, 0.2], [0, 0.2], [-0.2, 0.2], [-0.2, 0], [-0.2, 0], [-0.2, -0.2]], steps=1)
    el = sk.Curve.bezier([[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [3, 1, 0], [3, 2, 0], [3, 3, 0]], steps=2)
    for join in ("mitre", "round", "bevel"):
        lv, lf = sk.sweep(square, el, frames="sequential", join=join)
        solid = trimesh.Trimesh(lv, lf, process=False)
        assert solid.is_watertight and solid.is_winding_consistent and solid.volume > 0, join
    # the mitred L: the square's area times the centre line's length
    lv, lf = sk.sweep(square, el, frames="sequential")
    assert abs(trimesh.Trimesh(lv, lf, process=False).volume - 0.16 * 6) < 1e-9


def test_sweep_scale_twist_and_errors():
    path = sk.Curve.bezier([[0, 0, 0], [0, 0, 1], [0, 0, 2], [0, 0, 3]], steps=12)
    square = sk.Curve.bezier([[-1, -1], [0, -1], [0, -1], [1, -1], [1, 0], [1, 0], [1, 1], [0, 1], [0, 1], [-1, 1], [-1, 0], [-1, 0]], closed=True, steps=1)
    v0, _ = sk.sweep(square, path, caps=False)
    v1, _ = sk.sweep(square, path, scale=2.0, caps=False)
    np.testing.assert_allclose(np.abs(v1[:, :2]).max(), 2 * np.abs(v0[:, :2]).max())
    v2, _ = sk.sweep(square, path, twist=90.0, caps=False)
    # the last ring is the first turned by 90° about z
    first, last = v2[np.isclose(v2[:, 2], 0)], v2[np.isclose(v2[:, 2], 3)]
    np.testing.assert_allclose(np.sort(np.round(np.arctan2(last[:, 1], last[:, 0]), 9) % (2 * np.pi / 4)),
                               np.sort(np.round(np.arctan2(first[:, 1], first[:, 0]), 9) % (2 * np.pi / 4)), atol=1e-6)
    with pytest.raises(ValueError, match="profile must be a 2D curve"):
        sk.sweep(path, path)
    with pytest.raises(ValueError, match="unknown frames"):
        sk.sweep(square, path, frames="nope")
    with pytest.raises(ValueError, match="tolerance must be a positive number"):
        sk.sweep(square, path, tolerance=-1.0)
    # scale_mode="override": the scale is the profile's size, however large it was drawn
    corners = [[-1, -1], [0, -1], [0, -1], [1, -1], [1, 0], [1, 0], [1, 1], [0, 1], [0, 1], [-1, 1], [-1, 0], [-1, 0]]
    big = sk.Curve.bezier(5 * np.array(corners, dtype=float), closed=True, steps=1)
    v3, _ = sk.sweep(square, path, scale=(0.5, 0.25), scale_mode="override", caps=False)
    v4, _ = sk.sweep(big, path, scale=(0.5, 0.25), scale_mode="override", caps=False)
    np.testing.assert_allclose(v3, v4, atol=1e-12)
    # the corners (±1, ±1) go to (±0.5, ±0.25) about the path
    np.testing.assert_allclose(np.hypot(v3[:, 0], v3[:, 1]).max(), np.hypot(0.5, 0.25), atol=1e-12)
    v5, _ = sk.sweep(big, path, scale=(0.5, 0.25), caps=False)
    np.testing.assert_allclose(np.hypot(v5[:, 0], v5[:, 1]).max(), 5 * np.hypot(0.5, 0.25), atol=1e-12)
    with pytest.raises(ValueError, match="unknown scale_mode"):
        sk.sweep(square, path, scale_mode="add")


def icosahedron():
    t = (1 + 5**0.5) / 2
    v = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
                  [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], dtype=float)
    f = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
                  [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
                  [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]])
    return v, f


def cube():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    f = np.array([[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]])
    return v, f


def test_subdivision_counts():
    v, f = icosahedron()
    v1, f1 = sk.subdivide(v, f, 1)
    assert v1.shape == (42, 3) and f1.shape == (80, 3)
    v2, f2 = sk.subdivide(v, f, 2, scheme="loop", weights="warren")
    assert v2.shape == (162, 3) and f2.shape == (320, 3)
    cv, cf = cube()
    q1, qf1 = sk.subdivide(cv, cf, 1, scheme="catmull-clark")
    assert q1.shape == (8 + 12 + 6, 3) and qf1.shape == (24, 4)
    s1, sf1 = sk.subdivide(v, f, 1, scheme="sqrt3")
    assert len(s1) == 12 + 20 and len(sf1) == 60
    b1, bf1 = sk.subdivide(v, f, 1, scheme="butterfly")
    np.testing.assert_array_equal(b1[:12], v)  # interpolating
    d1, df1 = sk.subdivide(cv, cf, 1, scheme="doo-sabin")
    idx, off = df1  # a face per face (6 quads), edge (12 quads) and vertex (8 triangles): mixed sizes
    assert len(d1) == 24 and len(off) == 27 and off[-1] == len(idx) == 6 * 4 + 12 * 4 + 8 * 3


def test_loop_matches_opensubdiv(repo):
    data = repo / "crates" / "splinekit" / "tests" / "data" / "loop"
    v, f = sk.read_mesh(data / "icosphere80.in.obj")
    ref_v, ref_f = sk.read_mesh(data / "icosphere80.osd.l2.obj")
    v2, f2 = sk.subdivide(v, f, 2)
    assert v2.shape == ref_v.shape and f2.shape == ref_f.shape
    # OpenSubdiv numbers its vertices otherwise: match them by position
    mine, ref = np.lexsort(np.round(v2, 9).T), np.lexsort(np.round(ref_v, 9).T)
    np.testing.assert_allclose(v2[mine], ref_v[ref], rtol=0, atol=1e-12)
    to_ref = np.empty(len(v2), dtype=np.int64)
    to_ref[mine] = ref

    def canonical(faces):  # each triangle from its smallest vertex, orientation kept
        rolled = [np.roll(t, -int(np.argmin(t))) for t in faces]
        return sorted(map(tuple, rolled))

    assert canonical(to_ref[f2]) == canonical(ref_f)


def test_limit_positions_and_normals():
    v, f = icosahedron()
    lv, lf = sk.subdivide(v, f, 0, limit=True)
    r = np.linalg.norm(lv, axis=1)
    np.testing.assert_allclose(r, r[0], rtol=1e-12)  # symmetric: every vertex at the same limit radius
    n = sk.limit_normals(v, f)
    np.testing.assert_allclose(n, lv / r[:, None], atol=1e-12)  # the limit normal is radial here


def test_creases_keep_an_edge_sharp():
    cv, cf = cube()
    edges = np.array([[0, 1], [1, 3], [3, 2], [2, 0]])  # the x = 0 face's boundary
    smooth, _ = sk.subdivide(cv, cf, 3, scheme="catmull-clark")
    sharp, _ = sk.subdivide(cv, cf, 3, scheme="catmull-clark", creases=(edges, np.full(4, 10.0)))
    # with an infinitely sharp loop the x = 0 face stays flat at x = 0
    assert np.isclose(sharp[:, 0].min(), 0.0, atol=1e-12)
    assert smooth[:, 0].min() > 0.05


def test_mesh_files_round_trip(tmp_path):
    v, f = icosahedron()
    for ext in ("obj", "ply", "stl", "glb"):
        path = tmp_path / f"ico.{ext}"
        sk.write_mesh(path, v, f)
        rv, rf = sk.read_mesh(path)
        if ext == "stl":  # STL has no shared vertices: compare triangle corners
            np.testing.assert_allclose(rv[rf], v[f], atol=1e-6)
        else:
            np.testing.assert_array_equal(rf, f)
            np.testing.assert_allclose(rv, v, atol=1e-6 if ext in ("glb", "ply") else 0)
    cv, cf = cube()
    sk.write_mesh(tmp_path / "cube.obj", cv, cf, creases=(np.array([[0, 1]]), np.array([2.5])))
    rv, rf, (edges, sharpness) = sk.read_mesh(tmp_path / "cube.obj", creases=True)
    np.testing.assert_array_equal(rf, cf)
    assert edges.tolist() == [[0, 1]] and sharpness.tolist() == [2.5]
    # mixed polygons: (indices, offsets)
    mixed = (np.array([0, 1, 3, 2, 0, 4, 5]), np.array([0, 4, 7]))
    sk.write_mesh(tmp_path / "mixed.obj", cv, mixed)
    _, (idx, off) = sk.read_mesh(tmp_path / "mixed.obj")
    assert idx.tolist() == mixed[0].tolist() and off.tolist() == mixed[1].tolist()
