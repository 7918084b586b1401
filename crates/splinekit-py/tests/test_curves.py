"""Curves against closed forms and numpy references: evaluation, derivatives, curvature, arc
length and its inverse, flattening, frames."""

import math

import numpy as np
import pytest

import splinekit as sk

P = np.array([[0.0, 0.0], [30.0, 90.0], [70.0, -40.0], [100.0, 10.0]])


def bernstein(p, t):
    t = np.asarray(t, dtype=float)[..., None]
    s = 1.0 - t
    return s**3 * p[0] + 3 * s**2 * t * p[1] + 3 * s * t**2 * p[2] + t**3 * p[3]


def bernstein_d1(p, t):
    t = np.asarray(t, dtype=float)[..., None]
    s = 1.0 - t
    return 3 * s**2 * (p[1] - p[0]) + 6 * s * t * (p[2] - p[1]) + 3 * t**2 * (p[3] - p[2])


def test_version():
    assert isinstance(sk.__version__, str) and sk.__version__.count(".") == 2


def test_cubic_bezier_values_and_shapes():
    c = sk.Curve.bezier(P)
    assert (c.dim, c.num_segments, c.domain, c.closed, c.kind) == (2, 1, (0.0, 1.0), False, "bez2")
    t = np.linspace(0.0, 1.0, 101)
    np.testing.assert_allclose(c.evaluate(t), bernstein(P, t), rtol=0, atol=1e-12)
    np.testing.assert_allclose(c.derivative(t), bernstein_d1(P, t), rtol=0, atol=1e-11)
    # exact at the ends, scalars give one point
    assert c.evaluate(0.0).tolist() == [0.0, 0.0] and c.evaluate(1).tolist() == [100.0, 10.0]
    assert c.evaluate(0.5).shape == (2,)
    assert c.evaluate(t.reshape(101, 1)).shape == (101, 1, 2)
    assert c.evaluate([[0.1, 0.2], [0.3, 0.4]]).shape == (2, 2, 2)
    assert c.derivative(0.25, order=0).tolist() == c.evaluate(0.25).tolist()
    # the third derivative of a cubic is constant: 6(p3 − 3p2 + 3p1 − p0)
    np.testing.assert_allclose(c.derivative(t, order=3), np.broadcast_to(6 * (P[3] - 3 * P[2] + 3 * P[1] - P[0]), (101, 2)))


def test_curvature_of_circles():
    for r in (0.5, 1.0, 7.0):
        c = sk.Curve.circle(r)
        k = c.curvature(np.linspace(0, 1, 17))
        np.testing.assert_allclose(k, 1.0 / r, rtol=1e-12)
        assert abs(c.arclen() - 2 * math.pi * r) <= 1e-9
        assert isinstance(c.curvature(0.3), float)


def test_exact_nurbs_quarter_circle():
    w = math.sqrt(0.5)
    c = sk.Curve.nurbs([[1, 0], [1, 1], [0, 1]], weights=[1, w, 1], degree=2)
    p = c.evaluate(np.linspace(0, c.domain[1], 1001))
    np.testing.assert_allclose(np.hypot(p[:, 0], p[:, 1]), 1.0, rtol=0, atol=1e-14)
    assert abs(c.arclen(1e-12) - math.pi / 2) <= 1e-12


def test_bezier_circle_approximation_error():
    # four cubic quarters with k = 4/3·(√2 − 1): the radius errs by at most 2.7e-4
    k = 4.0 / 3.0 * (math.sqrt(2.0) - 1.0)
    pts = [[1, 0], [1, k], [k, 1], [0, 1], [-k, 1], [-1, k], [-1, 0], [-1, -k], [-k, -1], [0, -1], [k, -1], [1, -k]]
    c = sk.Curve.bezier(pts, closed=True)
    assert c.closed and c.num_segments == 4
    p = c.evaluate(np.linspace(0, 4, 4001))
    err = np.abs(np.hypot(p[:, 0], p[:, 1]) - 1.0)
    assert 2.6e-4 < err.max() < 2.8e-4
    assert abs(c.arclen() - 2 * math.pi) < 2e-3


def test_straight_line_arc_length_and_inverse():
    line = sk.Curve.bezier([[0, 0, 0], [1, 2, 2], [2, 4, 4], [3, 6, 6]])  # evenly spaced: unit speed·9
    assert abs(line.arclen() - 9.0) <= 1e-12
    s = np.linspace(0, 9, 19)
    np.testing.assert_allclose(line.inv_arclen(s), s / 9.0, rtol=0, atol=1e-10)
    assert line.inv_arclen(-1.0) == 0.0 and line.inv_arclen(100.0) == 1.0
    pts = line.resample(1.5)
    np.testing.assert_allclose(np.linalg.norm(np.diff(pts, axis=0), axis=1), 1.5, atol=1e-9)
    assert pts.shape == (7, 3)


@pytest.mark.parametrize("accuracy", [10.0**-k for k in range(1, 12)])
def test_arclen_accuracy_sweep(accuracy):
    c = sk.Curve.bezier(P)
    reference = c.arclen(5e-12)
    assert abs(c.arclen(accuracy) - reference) <= accuracy, accuracy
    s = np.linspace(0, reference, 7)
    u = c.inv_arclen(s, accuracy=accuracy)
    # s(u) measured back by a fine table of the same curve
    uu, ss = c.arclen_table(samples=200000, method="gauss3")
    back = np.interp(u, uu, ss)
    assert np.all(np.abs(back - s) <= accuracy + 1e-9), accuracy


def reference_scene():
    a = np.arange(8) / 7.0
    th = 2 * np.pi * a
    r = np.cos(2 * th)
    pts = np.stack([r * np.cos(th), r * np.sin(th), -0.5 + a], axis=1)
    return sk.Curve.catmull_rom(pts)


CHORD_S = [
    0.00000, 0.13984, 0.35788, 0.59640, 0.77689, 0.82383, 0.99348, 1.31196, 1.68453, 2.01578, 2.21177, 2.28435,
    2.43888, 2.63035, 2.78487, 2.85746, 3.05345, 3.38470, 3.75727, 4.07574, 4.24539, 4.29233, 4.47283, 4.71135,
    4.92939, 5.06923,
]


def test_reference_scene_arc_length_table():
    c = reference_scene()
    assert c.num_segments == 5
    u, s = c.arclen_table(5, "chord")
    np.testing.assert_allclose(u, np.arange(26) / 5.0, atol=1e-15)
    np.testing.assert_allclose(s, CHORD_S, rtol=0, atol=5e-6)
    assert round(c.arclen_table(5, "gauss3")[1][-1], 5) == 5.14943
    assert round(c.arclen(), 5) == 5.14760
    assert abs(np.interp(0.417, s, u) - 0.4496) < 5e-5


def test_reference_scene_from_the_example_file(repo):
    doc = sk.read_swp(repo / "examples" / "reference-scene.swp")
    c = doc.curves["scene"]
    assert c.kind == "cr3" and c.steps == 20
    np.testing.assert_allclose(c.arclen_table()[1], CHORD_S, atol=5e-6)


def test_flatten_modes():
    c = sk.Curve.bezier(P, steps=8)
    u, p = c.flatten()
    assert u.shape == (9,) and p.shape == (9, 2)
    assert c.flatten(steps=3)[0].tolist() == [0.0, 1 / 3, 2 / 3, 1.0]
    for tol in (1e-1, 1e-3, 1e-5):
        u, p = c.flatten(tolerance=tol)
        assert u[0] == 0.0 and u[-1] == 1.0 and np.all(np.diff(u) > 0)
        np.testing.assert_array_equal(p, c.evaluate(u))
        # every curve point between two vertices lies within tol of their chord
        for a, b, pa, pb in zip(u[:-1], u[1:], p[:-1], p[1:]):
            q = c.evaluate(np.linspace(a, b, 33))
            d = pb - pa
            t = np.clip(((q - pa) @ d) / max(d @ d, 1e-300), 0, 1)
            assert np.max(np.linalg.norm(q - (pa + t[:, None] * d), axis=1)) <= tol * (1 + 1e-9)
    coarse, fine = c.flatten(angle_tolerance=20)[0], c.flatten(angle_tolerance=2)[0]
    assert len(coarse) < len(fine)


def test_flatten_closed_repeats_first_point():
    c = sk.Curve.bspline([[0, 0], [2, 0], [2, 1], [0, 1]], closed=True)
    u, p = c.flatten(tolerance=1e-4)
    assert p[0].tolist() == p[-1].tolist() and u[-1] == c.num_segments


@pytest.mark.parametrize("kind", ["rmf", "sequential", "frenet", "zup"])
def test_frames_orthonormal_right_handed(kind):
    c = sk.Curve.helix(1.0, 0.5, 3.0)
    u = np.linspace(*c.domain, 200)
    t, n, b = c.frames(u, kind=kind)
    assert t.shape == n.shape == b.shape == (200, 3)
    for v in (t, n, b):
        np.testing.assert_allclose(np.linalg.norm(v, axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(np.einsum("ij,ij->i", t, n), 0.0, atol=1e-12)
    np.testing.assert_allclose(np.cross(t, n), b, atol=1e-12)
    d = c.derivative(u)
    np.testing.assert_allclose(t, d / np.linalg.norm(d, axis=1)[:, None], atol=1e-12)
    assert c.frames(0.5, kind=kind)[0].shape == (3,)


def test_rmf_has_no_twist_on_a_plane_curve():
    # a planar curve: the RMF normal stays in the plane's normal direction or in the plane
    c = sk.Curve.catmull_rom([[0, 0, 0], [1, 0, 0], [2, 1, 0], [3, 0, 0], [4, 0, 0]], alpha=0.5)
    t, n, b = c.frames(np.linspace(*c.domain, 100))
    # B stays ±z (within rounding) all along
    np.testing.assert_allclose(np.abs(b[:, 2]), 1.0, atol=1e-9)


def test_sequential_2d_normal_left_of_travel():
    c = sk.Curve.bezier([[0, 0], [1, 0], [2, 0], [3, 0]])
    t, n, b = c.frames([0.0, 0.5, 1.0], kind="sequential")
    np.testing.assert_allclose(n, [[0, 1, 0]] * 3, atol=1e-15)
    np.testing.assert_allclose(b, [[0, 0, 1]] * 3, atol=1e-15)


def test_hermite_matches_catmull_rom_with_its_tangents():
    pts = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [6.0, 1.0]])
    cr = sk.Curve.catmull_rom(pts)
    tangents = (pts[2:] - pts[:-2]) / 2.0
    her = sk.Curve.hermite(pts[1:-1], tangents)
    u = np.linspace(0, 2, 41)
    np.testing.assert_allclose(her.evaluate(u), cr.evaluate(u), atol=1e-13)


def test_bspline_against_de_boor_form():
    pts = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [3.0, 1.0, -1.0], [4.0, -1.0, 2.0], [6.0, 0.0, 1.0]])
    c = sk.Curve.bspline(pts)
    t = np.linspace(0, 1, 11)[:, None]
    for k in range(2):
        p0, p1, p2, p3 = pts[k : k + 4]
        b = ((1 - t) ** 3 * p0 + (3 * t**3 - 6 * t**2 + 4) * p1 + (-3 * t**3 + 3 * t**2 + 3 * t + 1) * p2 + t**3 * p3) / 6
        np.testing.assert_allclose(c.evaluate(k + t[:, 0]), b, atol=1e-13)


def test_bezier_n_and_trefoil():
    c = sk.Curve.bezier_n([[0, 0], [1, 2], [2, -2], [3, 2], [4, 0]])
    assert c.kind == "bezn2" and c.num_segments == 1
    np.testing.assert_allclose(c.evaluate(0.5), [2.0, 0.25])  # Bernstein weights 1, 4, 6, 4, 1 over 16
    k = sk.Curve.trefoil(1.0)
    assert k.closed and k.dim == 3 and k.arclen() > 0


def test_kochanek_bartels_is_hermite_with_its_tangents():
    pts = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [6.0, 1.0], [7.0, 3.0]])
    zero = sk.Curve.kochanek_bartels(pts)
    assert zero.kind == "tcb2" and zero.num_segments == 3
    u = np.linspace(0, 3, 61)
    np.testing.assert_allclose(zero.evaluate(u), sk.Curve.catmull_rom(pts).evaluate(u), atol=1e-13)
    # continuity 0: the tangent at key i is (1 − t)·((1 + b)·d0 + (1 − b)·d1)/2 on both sides
    t = np.array([0.0, 0.5, -0.3, 0.8, 0.2, 0.0])
    b = np.array([0.0, 0.4, -0.6, 0.1, 0.9, 0.0])
    kb = sk.Curve.kochanek_bartels(pts, tension=t, bias=b)
    d0, d1 = pts[1:-1] - pts[:-2], pts[2:] - pts[1:-1]
    tangents = (1 - t[1:-1, None]) * ((1 + b[1:-1, None]) * d0 + (1 - b[1:-1, None]) * d1) / 2
    her = sk.Curve.hermite(pts[1:-1], tangents)
    np.testing.assert_allclose(kb.evaluate(u), her.evaluate(u), atol=1e-13)
    with pytest.raises(ValueError, match="tension must be between -1 and 1"):
        sk.Curve.kochanek_bartels(pts, tension=2.0)
    with pytest.raises(ValueError, match="one value per key"):
        sk.Curve.kochanek_bartels(pts, bias=[0.0, 1.0])


def test_bessel_overhauser_on_equal_chords_is_catmull_rom():
    # a regular hexagon: every chord the same length, so the chord-length parabolas' tangents
    # are the uniform Catmull-Rom ones
    a = np.arange(6) * np.pi / 3
    hexagon = np.stack([np.cos(a), np.sin(a)], axis=1)
    bo = sk.Curve.bessel_overhauser(hexagon, closed=True)
    assert bo.kind == "bo2" and bo.num_segments == 6
    u = np.linspace(0, 6, 121)
    np.testing.assert_allclose(bo.evaluate(u), sk.Curve.catmull_rom(hexagon, closed=True).evaluate(u), atol=1e-13)
    # uneven chords: not Catmull-Rom, but still through every key
    pts = np.array([[0.0, 0.0, 0.0], [0.2, 0.1, 0.0], [3.0, 1.0, 1.0], [3.5, 3.0, 0.5], [6.0, 4.0, 0.0]])
    bo = sk.Curve.bessel_overhauser(pts)
    np.testing.assert_allclose(bo.evaluate(np.arange(3.0)), pts[1:-1], atol=1e-13)
    assert np.abs(bo.evaluate(0.5) - sk.Curve.catmull_rom(pts).evaluate(0.5)).max() > 1e-3
