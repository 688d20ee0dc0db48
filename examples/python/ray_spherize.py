"""Every mesh under a folder through Sphaera's sphere-tree, as Ray tasks; one table out.

    python examples/python/ray_spherize.py DIR --out trees.parquet
    python examples/python/ray_spherize.py DIR --out trees.parquet --address auto   # a cluster

Each mesh file (OBJ, PLY, STL, OFF, glTF, GLB) becomes one Ray task that loads it, builds
its sphere-tree and certifies each level's error. A mesh that fails (unreadable,
malformed, enclosing no volume) is recorded with its error, not fatal. Progress goes to
stderr. The table has one row per mesh, sorted by path: `mesh`, `status` (`ok` or
`failed`), `error`, `triangles`, `spheres` (per level), `levels` (per level, the spheres
as a flat list `x, y, z, r, x, y, z, r, ...`), `error_lower` and `error_upper` (per level,
certified), `seconds`.

Without Ray installed, or with `--local`, the same work runs in this process: the rows
are identical (the sphere-trees are deterministic), which the test suite checks.
See docs/scale.md for clusters and throughput.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import sphaera

EXTENSIONS = {".obj", ".ply", ".stl", ".off", ".gltf", ".glb"}


def spherize(path: str, root: str, depth: int, branch: int) -> dict:
    """One mesh's row: its sphere-tree, or the error that stopped it."""
    started = time.perf_counter()
    row = {
        "mesh": str(Path(path).relative_to(root)),
        "status": "ok",
        "error": None,
        "triangles": None,
        "spheres": None,
        "levels": None,
        "error_lower": None,
        "error_upper": None,
    }
    try:
        # Only regular files inside the folder are read (a link or a glTF buffer leading
        # out of it, a device or a pipe is refused): the folder is nobody's inspected input.
        mesh = sphaera.load(path, root=root)
        tree = sphaera.spheretree(mesh, depth=depth, branch=branch)
    except (OSError, ValueError) as error:  # PermissionError is an OSError
        row.update(status="failed", error=f"{type(error).__name__}: {error}")
    else:
        row.update(
            triangles=mesh.triangle_count,
            spheres=[len(level) for level in tree.levels],
            levels=[level.ravel().tolist() for level in tree.levels],
            error_lower=[e[0] if e else None for e in tree.errors],
            error_upper=[e[1] if e else None for e in tree.errors],
        )
    row["seconds"] = time.perf_counter() - started
    return row


def mesh_files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in EXTENSIONS)


def run_local(files, root, depth, branch, progress):
    rows = []
    for k, path in enumerate(files, 1):
        rows.append(spherize(str(path), str(root), depth, branch))
        progress(k, len(files))
    return rows


def run_ray(files, root, depth, branch, progress, address, num_cpus):
    import ray

    # One core per task: each worker's Sphaera runs on one thread (RAYON_NUM_THREADS), so
    # a node runs as many meshes at once as it has cores, none oversubscribed. The
    # results do not depend on the thread count.
    ray.init(
        address=address,
        num_cpus=num_cpus,
        include_dashboard=False,
        log_to_driver=False,
        runtime_env={"env_vars": {"RAYON_NUM_THREADS": "1"}},
    )
    try:
        task = ray.remote(num_cpus=1)(spherize)
        pending = [task.remote(str(path), str(root), depth, branch) for path in files]
        rows = []
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            rows.extend(ray.get(done))
            progress(len(rows), len(files))
        return rows
    finally:
        ray.shutdown()


def write_table(rows: list[dict], out: Path) -> None:
    import pyarrow as pa
    import pyarrow.parquet as pq

    rows = sorted(rows, key=lambda r: r["mesh"])
    schema = pa.schema(
        [
            ("mesh", pa.string()),
            ("status", pa.string()),
            ("error", pa.string()),
            ("triangles", pa.int64()),
            ("spheres", pa.list_(pa.int64())),
            ("levels", pa.list_(pa.list_(pa.float64()))),
            ("error_lower", pa.list_(pa.float64())),
            ("error_upper", pa.list_(pa.float64())),
            ("seconds", pa.float64()),
        ]
    )
    table = pa.Table.from_pylist(rows, schema=schema)
    partial = out.with_name(out.name + ".partial")
    pq.write_table(table, partial)
    partial.replace(out)  # atomically: a reader never sees half a table


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path, help="the folder of meshes (searched recursively)")
    parser.add_argument("--out", type=Path, required=True, help="the Parquet table to write")
    parser.add_argument("--depth", type=int, default=3)
    parser.add_argument("--branch", type=int, default=8)
    parser.add_argument("--address", default=None, help="a Ray cluster (`auto`); default: a local one")
    parser.add_argument("--num-cpus", type=int, default=None, help="CPUs of the local Ray cluster")
    parser.add_argument("--local", action="store_true", help="run in this process, without Ray")
    args = parser.parse_args(argv)
    if not args.folder.is_dir():
        parser.error(f"{args.folder} is not a folder")
    files = mesh_files(args.folder)
    if not files:
        parser.error(f"no mesh files under {args.folder}")

    started = time.perf_counter()

    def progress(done, total):
        print(f"\r{done}/{total} meshes, {time.perf_counter() - started:.1f} s", end="", file=sys.stderr, flush=True)

    if args.local:
        rows = run_local(files, args.folder, args.depth, args.branch, progress)
    else:
        rows = run_ray(files, args.folder, args.depth, args.branch, progress, args.address, args.num_cpus)
    print(file=sys.stderr)
    write_table(rows, args.out)
    failed = [r for r in rows if r["status"] != "ok"]
    print(
        f"{len(rows) - len(failed)} meshes spherized, {len(failed)} failed, "
        f"in {time.perf_counter() - started:.1f} s; table in {args.out}",
        file=sys.stderr,
    )
    for row in failed:
        print(f"  {row['mesh']}: {row['error']}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
