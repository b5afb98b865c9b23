#!/usr/bin/env python3
"""meshbool.dask against one machine: cut and fill of a generated terrain against pit shells,
whole (meshbool.cutfill in this process, one pit after the other) and tiled
(meshbool.dask.tiled_cutfill_many: every pit's tiles in one batch, on a LocalCluster of 1
and of 2 worker processes, one library thread per task).

Per run: wall time, the tiles, the largest relative difference of cut, fill and common
plan area from the whole's, and the peak resident memory of each worker process (its
VmHWM, read on the worker after the run; the cluster is new for each worker count).
The terrain is `meshbool.terrain` with --cells cells a side (2·cells² triangles), the pit
shells `meshbool.pit` spread over it.

    python3 -m venv /tmp/dv && /tmp/dv/bin/pip install "./crates/meshbool-py[dask]"
    /tmp/dv/bin/python bench/dask_cutfill.py --cells 1000 --pits 4 --tile 250
"""

import argparse
import resource
import time

import distributed

import meshbool
import meshbool.dask


def peak_rss_mb() -> float:
    """This process's peak resident memory (MB): VmHWM of /proc/self/status, the high-water
    mark of its own address space (ru_maxrss would count the parent's from before the
    worker's exec); ru_maxrss where /proc is absent."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cells", type=int, default=1000, help="terrain cells a side")
    ap.add_argument("--pits", type=int, default=4, help="pit shells")
    ap.add_argument("--tile", type=float, default=250.0, help="tile side (the terrain is 1000 wide)")
    ap.add_argument("--workers", default="1,2", help="worker counts to run")
    args = ap.parse_args()

    terrain = meshbool.terrain(cells=args.cells)
    pits = [
        meshbool.pit(center=(-250.0 + 500.0 * (k % 2), -250.0 + 500.0 * (k // 2 % 2), 60.0),
                     radius=(200.0, 150.0), segments=128)
        for k in range(args.pits)
    ]
    print(f"terrain: {len(terrain.faces):,} triangles; {len(pits)} pits of {len(pits[0].faces):,}")
    whole = []
    start = time.perf_counter()
    for p in pits:
        whole.append(meshbool.cutfill(p, terrain, threads=1)[0])
    t_whole = time.perf_counter() - start
    print(f"whole, this process, 1 thread: {t_whole:.2f} s, peak RSS {peak_rss_mb():.0f} MB")

    for n in [int(x) for x in args.workers.split(",")]:
        cluster = distributed.LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
            memory_limit=0,
        )
        client = distributed.Client(cluster)
        start = time.perf_counter()
        worst, tiles = 0.0, 0
        for (r, _), w in zip(meshbool.dask.tiled_cutfill_many(pits, terrain, args.tile, client), whole):
            tiles += r["tiles"]
            for key in ("cut", "fill", "common_plan_area"):
                worst = max(worst, abs(r[key] - w[key]) / max(abs(w[key]), 1e-300))
        elapsed = time.perf_counter() - start
        rss = sorted(client.run(peak_rss_mb).values())
        print(
            f"tiled, {n} worker(s): {elapsed:.2f} s ({t_whole / elapsed:.2f}x the whole), "
            f"{tiles} tiles, worst relative difference {worst:.1e}, "
            f"peak RSS per worker {', '.join(f'{m:.0f}' for m in rss)} MB"
        )
        client.close()
        cluster.close()


if __name__ == "__main__":
    main()
