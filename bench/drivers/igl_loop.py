#!/usr/bin/env python3
"""libigl Loop subdivision driver (PyPI `libigl`, in a venv: bench/install_peers.sh).

    igl_loop.py IN.obj -n LEVELS [--repeat R] [-o OUT.obj]

igl.loop(V, F, number_of_subdivs=LEVELS): Warren's beta (3/(8n), 3/16 for n = 3), boundary
edges midpoint, boundary vertices 3/4 p + 1/8 (a + b) with a, b the first and last neighbour
of igl.adjacency_list's sorted one-ring (corners not fixed). Timed: the call alone, per
repeat; not timed: reading and writing files and building the numpy arrays.
Prints {"vertices": V, "faces": F, "seconds": median, "all_seconds": [...]}.
"""

import argparse
import json
import statistics
import sys
import time
from importlib.metadata import version
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in bench/
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from meshgen import read_obj  # noqa: E402

import igl  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("input")
    ap.add_argument("-n", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("-o")
    a = ap.parse_args()
    positions, faces = read_obj(a.input)
    v = np.array(positions, dtype=np.float64)
    f = np.array(faces, dtype=np.int64)
    times = []
    nv = nf = None
    for _ in range(a.repeat):
        nv = nf = None  # free the previous result first, so peak memory holds one output
        t0 = time.perf_counter()
        nv, nf = igl.loop(v, f, a.n)
        times.append(time.perf_counter() - t0)
    if a.o:
        with open(a.o, "w", encoding="ascii", newline="\n") as out:
            out.write(f"# libigl {version('libigl')} (PyPI) igl.loop(V, F, number_of_subdivs={a.n})\n")
            for p in nv:
                out.write("v %.17g %.17g %.17g\n" % (p[0], p[1], p[2]))
            for t in nf:
                out.write(f"f {t[0] + 1} {t[1] + 1} {t[2] + 1}\n")
    print(json.dumps({"vertices": int(nv.shape[0]), "faces": int(nf.shape[0]),
                      "seconds": round(statistics.median(times), 6), "all_seconds": [round(t, 6) for t in times]}))


if __name__ == "__main__":
    main()
