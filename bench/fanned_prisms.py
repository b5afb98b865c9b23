"""Two prisms standing on one base, their caps triangulated as fans from one corner.

Each prism is an ellipse (semi-axes 50 and 25) of N sides extruded 10 high; the second is
turned by 0.3 radians about the common centre. Both caps of one prism lie in the planes
of the other's, and every cap is a fan of N - 2 long thin triangles from the ring's first
vertex, as CAD exports triangulate extruded profiles: the fans of the two caps cross each
other in a number of points that grows as N squared.

    python3 bench/fanned_prisms.py --bin target/release/meshbool --sides 500,2000
    python3 bench/fanned_prisms.py --bin target/release/meshbool --manifold   # needs manifold3d

Prints, per size and operation, the command's wall time (reading and writing included),
its peak resident memory, the result's volume and, with --manifold, manifold3d's time for
the same operation on the same meshes (its objects built before the timer).
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time


def ring(n, turn):
    """The ellipse's corners, counter-clockwise, turned by `turn` radians."""
    out = []
    for i in range(n):
        t = 2 * math.pi * i / n
        x, y = 50.0 * math.cos(t), 25.0 * math.sin(t)
        out.append((x * math.cos(turn) - y * math.sin(turn), x * math.sin(turn) + y * math.cos(turn)))
    return out


def prism(n, turn):
    """Vertices and triangles (0-based) of the fanned prism."""
    pts = ring(n, turn)
    verts = [(x, y, z) for z in (0.0, 10.0) for x, y in pts]
    tris = []
    for i in range(n):
        j = (i + 1) % n
        tris += [(i, j, n + j), (i, n + j, n + i)]
    for i in range(1, n - 1):
        tris += [(0, i + 1, i), (n, n + i, n + i + 1)]
    return verts, tris


def write_obj(path, verts, tris):
    with open(path, "w") as f:
        for v in verts:
            f.write("v %r %r %r\n" % v)
        for t in tris:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def run_cli(binary, op, a, b, out):
    """Wall time, peak resident memory (MiB) and the result's volume of one command."""
    start = time.perf_counter()
    proc = subprocess.run(
        ["/usr/bin/time", "-f", "%M", binary, op, a, b, "-o", out],
        capture_output=True,
        text=True,
    )
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        return wall, None, "failed: " + proc.stderr.strip().splitlines()[-1]
    peak = int(proc.stderr.strip().splitlines()[-1]) / 1024
    info = subprocess.run([binary, "info", out], capture_output=True, text=True).stdout
    volume = next(line.split()[1] for line in info.splitlines() if line.strip().startswith("volume"))
    return wall, peak, volume


def run_manifold(verts_a, tris_a, verts_b, tris_b):
    import manifold3d as m3
    import numpy as np

    def build(verts, tris):
        mesh = m3.Mesh(
            vert_properties=np.array(verts, dtype=np.float32),
            tri_verts=np.array(tris, dtype=np.uint32),
        )
        return m3.Manifold(mesh)

    a, b = build(verts_a, tris_a), build(verts_b, tris_b)
    times = {}
    for op, f in (("union", lambda: a + b), ("intersection", lambda: a ^ b), ("difference", lambda: a - b)):
        start = time.perf_counter()
        f().volume()
        times[op] = time.perf_counter() - start
    return times


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bin", default="target/release/meshbool")
    p.add_argument("--sides", default="200,500,2000", help="comma-separated ring sizes")
    p.add_argument("--manifold", action="store_true", help="time manifold3d too")
    args = p.parse_args()
    if not os.path.exists(args.bin):
        sys.exit(f"no binary at {args.bin}: cargo build --release -p meshbool-cli")
    print("| sides | triangles each | op | meshbool s | MiB | volume | manifold3d s |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in (int(s) for s in args.sides.split(",")):
            (va, ta), (vb, tb) = prism(n, 0.0), prism(n, 0.3)
            a, b = os.path.join(tmp, "a.obj"), os.path.join(tmp, "b.obj")
            write_obj(a, va, ta)
            write_obj(b, vb, tb)
            peer = run_manifold(va, ta, vb, tb) if args.manifold else {}
            for op in ("union", "intersection", "difference"):
                wall, peak, volume = run_cli(args.bin, op, a, b, os.path.join(tmp, "r.obj"))
                peak = "" if peak is None else "%.0f" % peak
                other = "%.2f" % peer[op] if op in peer else ""
                print(f"| {n} | {len(ta)} | {op} | {wall:.2f} | {peak} | {volume} | {other} |")


if __name__ == "__main__":
    main()
