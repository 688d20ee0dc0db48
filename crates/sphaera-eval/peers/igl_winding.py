"""Times libigl's fast winding number (Barill, Dickson, Schmidt, Levin & Jacobson,
SIGGRAPH 2018; the `libigl` package on PyPI, 2.6) on a closed mesh and a set of query
points: the 3D point-inclusion peer of the `hal3_vs_parry` bench of sphaera-eval.

    python3 -m venv env && env/bin/pip install libigl numpy
    env/bin/python igl_winding.py MESH.obj POINTS.txt [REPEATS] [RUNS]

POINTS.txt holds one point per line, three numbers separated by spaces. Each run calls
`igl.fast_winding_number(V, F, Q)` (the triangle-soup form: it builds its hierarchy and
evaluates the winding number at every row of Q) once on the points repeated REPEATS times
(default 1), and three times on the first point alone, all timed with
time.perf_counter; libigl's Python binding exposes no mesh precomputation to keep between
calls, so the quickest of the one-point calls measures the build and the call's overhead,
and `seconds`, the difference, the queries alone (repeat enough for the build's own
variation to be small beside them). Loading the files is not timed. One thread: IGL_NUM_THREADS (libigl's
`default_num_threads`) and OMP_NUM_THREADS are set to 1 before libigl is imported, unless
already set. Prints one JSON line per run (RUNS, default 1):

    {"seconds": s, "seconds_all": a, "seconds_one": o, "points": n, "inside": k,
     "threads": t}

where `seconds` is `a - o`, `points` the number of queries answered in `a` (the file's
points times REPEATS), `inside` the number of the file's points whose winding number
exceeds 1/2, and `threads` the thread count asked for.
"""

import json
import os
import sys
import time

os.environ.setdefault("IGL_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import igl  # noqa: E402  (after the thread count is set)
import numpy as np  # noqa: E402


def load_obj(path):
    """Vertices (float64) and triangles (int64, fan-split polygons) of an OBJ file."""
    vertices, faces = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
                for k in range(1, len(ids) - 1):
                    faces.append([ids[0], ids[k], ids[k + 1]])
    return (
        np.ascontiguousarray(vertices, dtype=np.float64),
        np.ascontiguousarray(faces, dtype=np.int64),
    )


def main():
    mesh, points = sys.argv[1], sys.argv[2]
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    runs = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    vertices, faces = load_obj(mesh)
    queries = np.ascontiguousarray(np.loadtxt(points, dtype=np.float64, ndmin=2))
    tiled = np.ascontiguousarray(np.tile(queries, (max(repeats, 1), 1)))
    first = np.ascontiguousarray(queries[:1])
    for _ in range(runs):
        start = time.perf_counter()
        winding = igl.fast_winding_number(vertices, faces, tiled)
        seconds_all = time.perf_counter() - start
        seconds_one = float("inf")
        for _ in range(3):
            start = time.perf_counter()
            igl.fast_winding_number(vertices, faces, first)
            seconds_one = min(seconds_one, time.perf_counter() - start)
        print(
            json.dumps(
                {
                    "seconds": max(seconds_all - seconds_one, 0.0),
                    "seconds_all": seconds_all,
                    "seconds_one": seconds_one,
                    "points": int(tiled.shape[0]),
                    "inside": int(np.count_nonzero(winding[: len(queries)] > 0.5)),
                    "threads": int(os.environ["IGL_NUM_THREADS"]),
                }
            ),
            flush=True,
        )


if __name__ == "__main__":
    main()
