"""The same numbers as the `splinekit` command line, bit for bit (the same library code runs)."""

import csv
import io
import json
import subprocess

import numpy as np
import pytest

import splinekit as sk


def run(cli, *args):
    return subprocess.run([cli, *map(str, args)], check=True, capture_output=True, text=True).stdout


def test_curve_points_and_frames(cli, repo):
    path = repo / "examples" / "reference-scene.swp"
    c = sk.read_swp(path).curves["scene"]
    for extra, kind, flatten in [
        (["--tolerance", "1e-4", "--frames", "rmf"], "rmf", {"tolerance": 1e-4}),
        (["--steps", "7"], "sequential", {"steps": 7}),
        (["--angle-tolerance", "3", "--frames", "frenet"], "frenet", {"angle_tolerance": 3.0}),
    ]:
        rows = list(csv.DictReader(io.StringIO(run(cli, "curve", path, *extra))))
        u, p = c.flatten(**flatten)
        t, n, b = c.frames(u, kind=kind)
        assert len(rows) == len(u)
        got = np.array([[float(r[k]) for k in "u x y z tx ty tz nx ny nz bx by bz".split()] for r in rows])
        mine = np.hstack([u[:, None], p, t, n, b]) + 0.0  # the CLI writes -0 as 0
        np.testing.assert_array_equal(got, mine)


def test_arc_length(cli, repo):
    path = repo / "examples" / "reference-scene.swp"
    c = sk.read_swp(path).curves["scene"]
    out = json.loads(run(cli, "arclen", path, "--method", "adaptive", "--accuracy", "1e-10", "--at-s", "0.417", "--at-s", "3", "--json"))
    assert out["length"] == c.arclen(1e-10)
    assert [q["u"] for q in out["at_s"]] == c.inv_arclen(np.array([0.417, 3.0]), accuracy=1e-10).tolist()
    table = json.loads(run(cli, "arclen", path, "--method", "gauss3", "--samples", "7", "--json"))["table"]
    u, s = c.arclen_table(7, "gauss3")
    assert [r["s"] for r in table] == s.tolist() and [r["u"] for r in table] == u.tolist()


def test_subdivision(cli, repo, tmp_path):
    src = repo / "crates" / "splinekit" / "tests" / "data" / "loop" / "torus96.in.obj"
    out = tmp_path / "torus.obj"
    run(cli, "subdivide", src, "-n", "2", "-o", out)
    v, f = sk.read_mesh(src)
    mine_v, mine_f = sk.subdivide(v, f, 2)
    cli_v, cli_f = sk.read_mesh(out)
    np.testing.assert_array_equal(cli_f, mine_f)
    np.testing.assert_array_equal(cli_v, mine_v)
