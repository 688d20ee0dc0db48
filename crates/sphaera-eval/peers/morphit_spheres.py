"""Runs MorphIt (the Rust port `morphit-rs`, PyPI 0.2.0, of the HIRO group's MorphIt,
arXiv 2507.14061) on a mesh for several sphere counts: the peer of the
`spheres_vs_count` experiment and the `spheres_vs_morphit` bench of sphaera-eval.

    python3 -m venv env && env/bin/pip install morphit-rs==0.2.0 numpy
    env/bin/python morphit_spheres.py MESH N1,N2,... RUNS [--preset NAME]
                                      [--seed S] [--threads T]

For each N: `morphit_rs.pack(mesh, Config.preset(NAME, num_spheres=N, seed=S))`, the
preset's whole schedule (MorphIt-B by default: 300 Adam iterations on 5,000 interior and
5,000 surface samples, count-preserving density control, then a final prune of the
spheres whose centre left the mesh). Only the `pack` call is timed (time.perf_counter;
loading the mesh and making the config are not). Prints one JSON line per N:

    {"n": N, "n_returned": K, "seconds": s, "seconds_median": m, "seconds_all": [...],
     "centers": [[x, y, z], ...], "radii": [...], "preset": ..., "seed": ..., "threads": ...}

`seconds` is the shortest of RUNS runs (as sphaera-eval times Sphaera), `seconds_median`
their median, `seconds_all` every run's; the spheres are those of the first run (with a seed the runs are
identical). K < N when the final prune removed escaped spheres: MorphIt does not promise
exactly N. A count whose `pack` raises prints `{"n": N, "error": "..."}` instead, and the
script goes on with the next count.

MorphIt draws its seed from OS entropy when none is given; here the seed defaults to 0,
so the output is reproducible. The package uses every core by default (rayon);
`--threads T` (or RAYON_NUM_THREADS) sets its pool size.
"""

import argparse
import json
import statistics
import time

import morphit_rs as mi


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("counts", help="comma-separated sphere counts, e.g. 8,16,32")
    ap.add_argument("runs", type=int)
    ap.add_argument("--preset", default="MorphIt-B", choices=mi.presets())
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=0, help="0: the package default (all cores)")
    args = ap.parse_args()
    if args.threads > 0:
        mi.set_num_threads(args.threads)

    mesh = mi.Mesh.load(args.mesh)
    for n in (int(s) for s in args.counts.split(",") if s):
        times, first = [], None
        try:
            for _ in range(max(args.runs, 1)):
                config = mi.Config.preset(args.preset, num_spheres=n, seed=args.seed)
                t0 = time.perf_counter()
                result = mi.pack(mesh, config)
                times.append(time.perf_counter() - t0)
                if first is None:
                    first = result
        except Exception as error:  # the peer failing on one count is a result, not a crash
            print(json.dumps({"n": n, "error": str(error)}), flush=True)
            continue
        print(json.dumps({
            "n": n,
            "n_returned": len(first),
            "seconds": min(times),
            "seconds_median": statistics.median(times),
            "seconds_all": times,
            "centers": first.centers.tolist(),
            "radii": first.radii.tolist(),
            "preset": args.preset,
            "seed": args.seed,
            "threads": args.threads or "default",
        }), flush=True)


if __name__ == "__main__":
    main()
