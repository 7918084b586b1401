"""Bad input raises ValueError (OSError for files) with the library's messages; no memory grows
over many calls."""

import os

import numpy as np
import pytest

import splinekit as sk


def test_bad_points():
    with pytest.raises(ValueError, match="control point 1 is not finite"):
        sk.Curve.bezier([[0, 0], [np.nan, 1], [2, 2], [3, 3]])
    with pytest.raises(ValueError, match=r"shape \(n, 2\) or \(n, 3\), got shape \(4,\)"):
        sk.Curve.bspline([0, 1, 2, 3])
    with pytest.raises(ValueError, match=r"got shape \(4, 4\)"):
        sk.Curve.bspline(np.zeros((4, 4)))
    with pytest.raises(ValueError, match="bezier needs 3m\\+1 control points|control points, got 5"):
        sk.Curve.bezier(np.zeros((5, 2)))
    with pytest.raises(ValueError, match="at least 4 control points, got 3"):
        sk.Curve.bspline(np.zeros((3, 2)))
    with pytest.raises(ValueError, match=r"alpha must be in \[0, 1\], got 2"):
        sk.Curve.catmull_rom(np.zeros((4, 2)), alpha=2.0)
    with pytest.raises(ValueError, match="one tangent per point"):
        sk.Curve.hermite(np.zeros((3, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="must be a number or an array"):
        sk.Curve.bspline([["a", "b"]] * 4)


def test_bad_arguments():
    c = sk.Curve.bezier([[0, 0], [1, 1], [2, 1], [3, 0]])
    with pytest.raises(ValueError, match="accuracy must be a positive number, got 0"):
        c.arclen(0.0)
    with pytest.raises(ValueError, match="accuracy must be a positive number, got NaN"):
        c.inv_arclen(1.0, accuracy=float("nan"))
    with pytest.raises(ValueError, match="spacing must be a positive number, got -1"):
        c.resample(-1.0)
    with pytest.raises(ValueError, match="tolerance must be a positive number"):
        c.flatten(tolerance=0.0)
    with pytest.raises(ValueError, match="at most one of"):
        c.flatten(tolerance=0.1, steps=3)
    with pytest.raises(ValueError, match="unknown frames"):
        c.frames([0.0, 1.0], kind="bishop")
    with pytest.raises(ValueError, match="order must be"):
        c.derivative(0.5, order=4)


def test_bad_meshes():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    with pytest.raises(ValueError, match="unknown scheme nope"):
        sk.subdivide(v, f, 1, scheme="nope")
    with pytest.raises(ValueError, match="refers to vertex 9"):
        sk.subdivide(v, np.array([[0, 1, 9]]), 1)
    with pytest.raises(ValueError, match="vertex 1 is not finite"):
        sk.subdivide(np.where(np.arange(12).reshape(4, 3) == 3, np.nan, v), f, 1)
    with pytest.raises(ValueError, match=r"shape \(V, 3\)"):
        sk.subdivide(v[:, :2], f, 1)
    quad = (np.array([0, 1, 2, 3]), np.array([0, 4]))
    with pytest.raises(ValueError, match="triangle"):
        sk.subdivide(v, quad, 1, scheme="loop")
    with pytest.raises(ValueError, match="creases are for Loop and Catmull-Clark"):
        sk.subdivide(v, f, 1, scheme="sqrt3", creases=(np.array([[0, 1]]), np.array([1.0])))
    with pytest.raises(ValueError, match="weights chooses"):
        sk.subdivide(v, f, 1, scheme="butterfly", weights="warren")


def test_missing_and_bad_files(tmp_path):
    with pytest.raises(FileNotFoundError):
        sk.read_swp(tmp_path / "missing.swp")
    with pytest.raises(FileNotFoundError):
        sk.read_mesh(tmp_path / "missing.obj")
    bad = tmp_path / "bad.swp"
    bad.write_text("bez2 . 20 4\n[0 0]\n[1 1.2.3]")
    with pytest.raises(ValueError, match=r'bad.swp:3:4: found "1.2.3", expected a number'):
        sk.read_swp(bad)
    v = np.zeros((3, 3))
    with pytest.raises(ValueError, match="unknown output format"):
        sk.write_mesh(tmp_path / "x.xyz", v, [[0, 1, 2]])
    with pytest.raises(OSError):
        sk.write_mesh(tmp_path / "no-such-dir" / "x.obj", np.eye(3), [[0, 1, 2]])
    assert not (tmp_path / "no-such-dir").exists()


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="needs /proc (Linux)")
def test_no_memory_growth_over_10000_calls():
    c = sk.Curve.catmull_rom(np.random.default_rng(1).random((12, 3)), alpha=0.5)
    u = np.linspace(0, c.num_segments, 64)
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])

    def work(i):
        c.evaluate(u)
        c.frames(u)
        c.inv_arclen(0.1 * (i % 10), accuracy=1e-6)
        sk.subdivide(v, f, 1)
        try:
            sk.Curve.bezier(np.zeros((5, 2)))
        except ValueError:
            pass

    for i in range(1000):  # warm up allocator pools
        work(i)
    before = rss_bytes()
    for i in range(10_000):
        work(i)
    grown = rss_bytes() - before
    assert grown < 8 * 2**20, f"resident memory grew by {grown / 2**20:.1f} MiB over 10 000 calls"
