#!/usr/bin/env python3
"""CSG documents in one Python process: meshbool.csg beside manifold3d (optional), same
meshes, same run.

Two cases:
- molecule: the union of N parts (atoms: UV spheres; bonds: cylinders between neighbours
  on a helix), in one call: meshbool.csg of a union node over the parts as meshes in
  memory, against manifold3d's Manifold.batch_boolean(parts, Add) (its Manifolds built
  before the timer; their building timed apart);
- housing: a 50-node scene, a plate with bosses and walls (a union) less 33 drilled holes
  (cutters) and a plane cut, evaluated cold, again unchanged (the root from the cache), and after
  one hole is moved (its path recomputed); manifold3d computes the same booleans
  (batch_boolean of the body, then of the cutters, then a difference) and, having no
  cache, all of them again after the edit.

Each time is the median of --reps runs. Every result's volume is printed beside
manifold3d's.

    python3 -m venv /tmp/benchv && /tmp/benchv/bin/pip install numpy manifold3d ./crates/meshbool-py
    /tmp/benchv/bin/python bench/csg.py --reps 5
"""

import argparse
import math
import statistics
import time

import meshbool

#: Holes drilled through the housing (three rows).
HOLES = 33


def median_ms(f, reps):
    """The median time of `f()` over `reps` runs, in ms, and its last result."""
    times, out = [], None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = f()
        times.append((time.perf_counter() - t0) * 1e3)
    return statistics.median(times), out


def primitive(spec):
    """The mesh of one primitive node (meshbool's tessellation, shared by both libraries)."""
    return meshbool.csg({"root": spec})


def molecule_parts(atoms):
    parts = []
    for k in range(atoms):
        a = k * 0.7
        x, y, z = 4 * math.cos(a), 4 * math.sin(a), k * 0.9
        parts.append({"primitive": "sphere", "center": [x, y, z], "radius": 1.1,
                      "segments": 16, "rings": 8})
        if k + 1 < atoms:
            b = (k + 1) * 0.7
            d = [4 * math.cos(b) - x, 4 * math.sin(b) - y, 0.9]
            length = math.sqrt(sum(c * c for c in d))
            angle = math.degrees(math.acos(d[2] / length))
            parts.append({"primitive": "cylinder", "radius": 0.35, "height": length,
                          "segments": 12, "transform": [
                              {"rotate": [-d[1], d[0], 0, angle]}, {"translate": [x, y, z]}]})
    return parts


def housing(hole_shift=0.0):
    body = [{"primitive": "cube", "min": [0, 0, 0], "max": [60, 40, 4]}]
    for i in range(3):
        for j in range(3):
            body.append({"primitive": "cylinder", "base": [10 + 20 * i, 8 + 12 * j, 4],
                         "radius": 3, "height": 6, "segments": 48})
    body.extend({"primitive": "cube", "min": [2 + 14 * k, 36, 0], "max": [8 + 14 * k, 40, 12]}
                for k in range(4))
    holes = []
    per_row = HOLES // 3
    for k in range(HOLES):
        x = 4 + 52 * (k % per_row) / (per_row - 1) + (hole_shift if k == 0 else 0)
        y = 6 + 14 * (k // per_row)
        holes.append({"primitive": "cylinder", "base": [x, y, -1], "radius": 0.8,
                      "height": 20, "segments": 32, "role": "cutter"})
    cut = {"primitive": "plane", "width": 200, "depth": 200, "role": "cutter",
           "transform": [{"rotate": ["x", 180]}, {"translate": [0, 0, 9]}]}
    root = {"op": "difference", "name": "housing", "children": [
        {"op": "union", "name": "body", "children": body}, *holes, cut]}
    return {"root": root}


def count_nodes(node):
    return 1 + sum(count_nodes(c) for c in node.get("children", []))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--atoms", type=int, default=500, help="atoms of the molecule (parts: 2N − 1)")
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    try:
        import manifold3d as m3d
    except ImportError:
        m3d = None

    def manifold(mesh):
        return m3d.Manifold(m3d.Mesh(vert_properties=mesh.vertices.astype("float32"),
                                     tri_verts=mesh.faces))

    from importlib.metadata import version
    print(f"meshbool {meshbool.__version__}" + (f", manifold3d {version('manifold3d')}" if m3d else ""))
    print()
    print("| case | meshbool (ms) | manifold3d (ms) | meshbool ÷ manifold3d | meshbool volume | manifold3d volume |")
    print("|---|---|---|---|---|---|")

    # The molecule: parts as meshes in memory (generated before the timer).
    specs = molecule_parts(args.atoms)
    meshes = [primitive(s) for s in specs]
    tris = sum(len(m) for m in meshes)
    scene = {"root": {"op": "union", "children": [{"mesh": m} for m in meshes]}}
    ours, out = median_ms(lambda: meshbool.csg(scene, threads=args.threads), args.reps)
    assert out.is_closed
    row = [f"molecule union, {len(meshes)} parts, {tris} triangles", f"{ours:.1f}"]
    if m3d:
        built_ms, solids = median_ms(lambda: [manifold(m) for m in meshes], 1)
        def union():
            # num_tri forces the evaluation (manifold3d's booleans are lazy).
            r = m3d.Manifold.batch_boolean(solids, m3d.OpType.Add)
            r.num_tri()
            return r
        theirs, res = median_ms(union, args.reps)
        row += [f"{theirs:.1f} (+{built_ms:.0f} to build)", f"{ours / theirs:.2f}",
                f"{out.volume:.6f}", f"{res.volume():.6f}"]
    else:
        row += ["", "", f"{out.volume:.6f}", ""]
    print("| " + " | ".join(row) + " |")

    # The housing: cold, warm, after one edit.
    doc, edited = housing(), housing(hole_shift=0.5)
    nodes = count_nodes(doc["root"])

    def cold():
        return meshbool.csg(doc, threads=args.threads)

    cold_ms, out = median_ms(cold, args.reps)
    assert out.is_closed, out.report
    cache = meshbool.CsgCache()
    meshbool.csg(doc, cache=cache, threads=args.threads)

    def warm():
        return meshbool.csg(doc, cache=cache, threads=args.threads)

    warm_ms, _ = median_ms(warm, args.reps)

    def edit():
        # Each run starts from the cache of the unedited scene.
        c = meshbool.CsgCache()
        meshbool.csg(doc, cache=c, threads=args.threads)
        t0 = time.perf_counter()
        r = meshbool.csg(edited, cache=c, threads=args.threads)
        return (time.perf_counter() - t0) * 1e3, r

    runs = [edit() for _ in range(args.reps)]
    edit_ms = statistics.median(t for t, _ in runs)
    after = runs[-1][1]
    computed = after.report["computed"]
    if m3d:
        body = [manifold(primitive(s)) for s in doc["root"]["children"][0]["children"]]

        def theirs_of(d):
            cutters = [manifold(primitive({k: v for k, v in s.items() if k != "role"}))
                       for s in d["root"]["children"][1:1 + HOLES]]
            cut_box = m3d.Manifold.cube([200, 200, 100]).translate([-100, -100, 9])

            def run():
                b = m3d.Manifold.batch_boolean(body, m3d.OpType.Add)
                c = m3d.Manifold.batch_boolean(cutters + [cut_box], m3d.OpType.Add)
                r = b - c
                r.num_tri()  # forces the evaluation (manifold3d's booleans are lazy)
                return r
            return run

        theirs_cold, res = median_ms(theirs_of(doc), args.reps)
        theirs_edit, res_edit = median_ms(theirs_of(edited), args.reps)
    for label, ms, peer, vol, peer_vol in [
        (f"housing, {nodes} nodes, cold", cold_ms, theirs_cold if m3d else None, out.volume,
         res.volume() if m3d else None),
        ("housing, unchanged (root from the cache)", warm_ms, None, out.volume, None),
        (f"housing, one hole moved ({computed} nodes computed)", edit_ms,
         theirs_edit if m3d else None, after.volume, res_edit.volume() if m3d else None),
    ]:
        row = [label, f"{ms:.2f}", f"{peer:.1f}" if peer else "", f"{ms / peer:.3f}" if peer else "",
               f"{vol:.6f}", f"{peer_vol:.6f}" if peer_vol else ""]
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
