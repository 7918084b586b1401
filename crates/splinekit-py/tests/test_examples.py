"""The example script runs and writes its meshes."""

import subprocess
import sys

import splinekit as sk


def test_trefoil_and_bunny_example(repo, tmp_path):
    script = repo / "examples" / "python" / "trefoil_and_bunny.py"
    subprocess.run([sys.executable, str(script), str(tmp_path)], check=True, capture_output=True)
    v, f = sk.read_mesh(tmp_path / "bunny-creased.obj")
    assert f.shape == (4968 * 16, 3)
    v, f = sk.read_mesh(tmp_path / "trefoil-tube.glb")
    assert len(f) == 23040
