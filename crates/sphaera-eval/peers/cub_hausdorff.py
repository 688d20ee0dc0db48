"""Times cascading-upper-bounds (Sacht & Jacobson, SGP 2024; `pip install
cascading_upper_bounds`) on a pair of OBJ meshes, for the Hausdorff comparison in
docs/benchmarks.md.

    python cub_hausdorff.py A.obj B.obj [RELATIVE_TOLERANCE] [RUNS]

The tolerance is relative to the bounding-box diagonal of both meshes together (as
Sphaera's `Length::RelativeToDiagonal`); it is converted to an absolute tolerance here.
The symmetric distance is the larger of the two one-sided runs, each timed (the package
computes one direction per call). Prints one JSON line per run: seconds (both
directions, loading excluded), lower and upper bounds.
"""

import json
import sys
import time

import numpy as np
from cascading_upper_bounds import pompeiu_hausdorff


def load_obj(path):
    """Vertices (float64) and triangles (int32, fan-split polygons) of an OBJ file."""
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
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    # Vertices no triangle uses are not points of the surface, but the package samples
    # them: drop them (the Stanford bunny has 1,113, one of them 1.2e-3 away).
    used, faces = np.unique(faces, return_inverse=True)
    faces = faces.reshape(-1, 3)
    return np.ascontiguousarray(vertices[used]), np.ascontiguousarray(faces, dtype=np.int32)


def main():
    path_a, path_b = sys.argv[1], sys.argv[2]
    relative = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-5
    runs = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    va, fa = load_obj(path_a)
    vb, fb = load_obj(path_b)
    both = np.vstack([va, vb])
    diagonal = float(np.linalg.norm(both.max(axis=0) - both.min(axis=0)))
    tolerance = relative * diagonal
    for _ in range(runs):
        start = time.perf_counter()
        ab = pompeiu_hausdorff(va, fa, vb, fb, tolerance, 1e6, False)
        ba = pompeiu_hausdorff(vb, fb, va, fa, tolerance, 1e6, False)
        seconds = time.perf_counter() - start
        print(
            json.dumps(
                {
                    "seconds": seconds,
                    "lower": max(ab[0], ba[0]),
                    "upper": max(ab[1], ba[1]),
                    "a_to_b": list(ab),
                    "b_to_a": list(ba),
                }
            )
        )


if __name__ == "__main__":
    main()
