"""Runs MorphIt's robot pipeline (`morphit_rs.RobotPackage`, PyPI `morphit-rs` 0.2.0) on a
URDF's folder for several sphere counts per link: the peer of sphaera-eval's
`robot_vs_morphit` experiment.

    python3 -m venv env && env/bin/pip install morphit-rs==0.2.0 numpy
    env/bin/python morphit_robot.py FOLDER URDF N1,N2,... [--seed S] [--threads T]

For each N: `RobotPackage.from_folder(FOLDER).pack_all(urdf=URDF, num_spheres=N,
seed=S, device="cpu")`, the package's defaults otherwise (MorphIt-B, 200 iterations),
timed as a whole (time.perf_counter; loading the package and `inspect` are not timed).
Prints one JSON line per N:

    {"n": N, "seconds": s, "links": [{"link": name, "index": i, "centers": [[x, y, z], ...],
      "radii": [...], "origin_xyz": [...], "origin_rpy": [...], "mesh_scale": [...]}, ...]}

with each collision's spheres as `pack_all` returns them and the collision's placement
in its link (from `inspect`), so that the caller puts them in the link's frame. A count
whose `pack_all` raises prints `{"n": N, "error": "..."}` and the script goes on.
"""

import argparse
import json
import time

import morphit_rs as mi


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder")
    ap.add_argument("urdf")
    ap.add_argument("counts", help="comma-separated sphere counts per link, e.g. 8,20")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=0, help="0: the package default (all cores)")
    args = ap.parse_args()
    if args.threads > 0:
        mi.set_num_threads(args.threads)
    package = mi.RobotPackage.from_folder(args.folder)
    items = {
        (c["link_name"], c["collision_index"]): c
        for c in package.inspect(args.urdf)["collisions"]
        if c["action"] == "pack"
    }
    for n in (int(s) for s in args.counts.split(",") if s):
        package.clear_link_results()
        try:
            t0 = time.perf_counter()
            results = package.pack_all(urdf=args.urdf, num_spheres=n, seed=args.seed, device="cpu")
            seconds = time.perf_counter() - t0
        except Exception as error:  # the peer failing on one count is a result, not a crash
            print(json.dumps({"n": n, "error": str(error)}), flush=True)
            continue
        links = []
        for (link, index), result in sorted(results.items()):
            item = items[(link, index)]
            links.append(
                {
                    "link": link,
                    "index": index,
                    "centers": [list(map(float, c)) for c in result.centers],
                    "radii": [float(r) for r in result.radii],
                    "origin_xyz": list(item["origin_xyz"]),
                    "origin_rpy": list(item["origin_rpy"]),
                    "mesh_scale": list(item["mesh_scale"]),
                }
            )
        print(json.dumps({"n": n, "seconds": seconds, "links": links}), flush=True)


if __name__ == "__main__":
    main()
