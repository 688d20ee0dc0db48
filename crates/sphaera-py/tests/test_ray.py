"""`examples/python/ray_spherize.py` on a local Ray cluster: the same table as in one
process, a corrupt mesh recorded and skipped."""

import shutil
import subprocess
import sys

import numpy as np

import sphaera
from conftest import REPOSITORY, required

SCRIPT = REPOSITORY / "examples" / "python" / "ray_spherize.py"


def run(folder, out, *extra):
    result = subprocess.run(
        [sys.executable, str(SCRIPT), str(folder), "--out", str(out), "--depth", "2", *extra],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    return result.stderr


def test_a_folder_on_a_local_ray_cluster_matches_one_process(tmp_path, data_dir):
    required("ray")
    pq = required("pyarrow.parquet")
    folder = tmp_path / "meshes"
    (folder / "nested").mkdir(parents=True)
    for name in ["bunny_lowres.obj", "spot.obj", "eight.off"]:
        shutil.copy(data_dir / name, folder / name)
    shutil.copy(data_dir / "fandisk.obj", folder / "nested" / "fandisk.obj")
    (folder / "corrupt.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    (folder / "notes.txt").write_text("not a mesh")

    ray_table = tmp_path / "ray.parquet"
    log = run(folder, ray_table, "--num-cpus", "2")
    assert "4 meshes spherized, 1 failed" in log and "corrupt.obj" in log
    local_table = tmp_path / "local.parquet"
    run(folder, local_table, "--local")

    ray_rows = pq.read_table(ray_table).to_pylist()
    local_rows = pq.read_table(local_table).to_pylist()
    assert [r["mesh"] for r in ray_rows] == sorted(
        ["bunny_lowres.obj", "spot.obj", "eight.off", "nested/fandisk.obj", "corrupt.obj"]
    )
    for a, b in zip(ray_rows, local_rows, strict=True):
        for key in ["mesh", "status", "error", "triangles", "spheres", "levels", "error_lower", "error_upper"]:
            assert a[key] == b[key], (a["mesh"], key)
    corrupt = next(r for r in ray_rows if r["mesh"] == "corrupt.obj")
    assert corrupt["status"] == "failed" and corrupt["error"].startswith("ValueError")
    # The table holds what the library gives in this process.
    bunny = next(r for r in ray_rows if r["mesh"] == "bunny_lowres.obj")
    tree = sphaera.spheretree(sphaera.load(data_dir / "bunny_lowres.obj"), depth=2)
    for flat, level in zip(bunny["levels"], tree.levels, strict=True):
        np.testing.assert_array_equal(np.asarray(flat).reshape(-1, 4), level)
    assert bunny["error_upper"] == [e[1] for e in tree.errors]
