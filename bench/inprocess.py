#!/usr/bin/env python3
"""Booleans in one Python process: meshbool beside manifold3d, trueform and meshlib (each
optional), on the meshes of ../shared/bench/gen_meshes.py, same process, same run.

For every case, operation and library, two medians over the repetitions:
- core: the boolean call alone (each library's own mesh objects already built; for
  meshbool, `meshbool.Operand`s: welded and checked);
- numpy: numpy arrays in -> numpy arrays out (building the library's objects and
  extracting the result included).
Every result's volume is checked against the inclusion-exclusion identity of the run.

    python3 -m venv venv && venv/bin/pip install ./crates/meshbool-py numpy \\
        manifold3d trueform meshlib
    venv/bin/python ../shared/bench/gen_meshes.py --out /tmp/meshes
    venv/bin/python bench/inprocess.py /tmp/meshes --reps 5 > results.md
    venv/bin/python bench/inprocess.py /tmp/meshes --real ../shared/data/real \\
        --cases thingi_79741_65004,thingi_908460_73416,sphere_5k --reps 5

meshbool runs with ``self_check=False`` as the peers check nothing (the default check
is reported in its own column).
"""

import argparse
import json
import os
import statistics
import sys
import time

import numpy as np

import meshbool

OPS = ("union", "intersection", "difference")


class Meshbool:
    name = "meshbool"

    def __init__(self, self_check=False):
        self.self_check = self_check
        if self_check:
            self.name = "meshbool (checked)"

    def prepare(self, v, f):
        # Welded and checked before the timer, as the peers build their objects.
        return meshbool.Operand((v, f), self_check=self.self_check)

    def boolean(self, a, b, op):
        return meshbool.boolean(a, b, op, self_check=self.self_check)

    def extract(self, r):
        return r.vertices, r.faces


class Manifold3d:
    name = "manifold3d"

    def __init__(self):
        import manifold3d

        self.m = manifold3d

    def prepare(self, v, f):
        mesh = self.m.Mesh64(np.ascontiguousarray(v), np.ascontiguousarray(f, dtype=np.uint64))
        return self.m.Manifold(mesh)

    def boolean(self, a, b, op):
        r = {"union": a + b, "intersection": a ^ b, "difference": a - b}[op]
        r.num_tri()  # evaluated lazily: force it inside the timing
        return r

    def extract(self, r):
        m = r.to_mesh64()
        return np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts)


class Trueform:
    name = "trueform"

    def __init__(self):
        import trueform

        self.tf = trueform

    def prepare(self, v, f):
        return self.tf.Mesh(np.ascontiguousarray(f, dtype=np.int32), np.ascontiguousarray(v))

    def boolean(self, a, b, op):
        fn = {
            "union": self.tf.boolean_union,
            "intersection": self.tf.boolean_intersection,
            "difference": self.tf.boolean_difference,
        }[op]
        (faces, points), _, _ = fn(a, b)
        return faces, points

    def extract(self, r):
        return np.asarray(r[1]), np.asarray(r[0])


class Meshlib:
    name = "meshlib"

    def __init__(self):
        import meshlib.mrmeshnumpy as mn
        import meshlib.mrmeshpy as mr

        self.mr, self.mn = mr, mn

    def prepare(self, v, f):
        return self.mn.meshFromFacesVerts(
            np.ascontiguousarray(f, dtype=np.int32), np.ascontiguousarray(v, dtype=np.float32)
        )

    def boolean(self, a, b, op):
        kind = self.mr.BooleanOperation
        o = {"union": kind.Union, "intersection": kind.Intersection, "difference": kind.DifferenceAB}
        r = self.mr.boolean(a, b, o[op])
        if not r.valid():
            raise RuntimeError(r.errorString)
        return r

    def extract(self, r):
        m = r.mesh
        m.pack()
        return self.mn.getNumpyVerts(m), self.mn.getNumpyFaces(m.topology)


def volume(v, f):
    v = np.asarray(v, dtype=np.float64)
    f = np.asarray(f, dtype=np.int64)
    if len(f) == 0:
        return 0.0
    c = v.mean(axis=0)
    p = v[f] - c
    return float(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0)


def median_time(fn, reps):
    times, out = [], None
    for _ in range(reps):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def libraries(names):
    libs = [Meshbool(), Meshbool(self_check=True)]
    for cls in (Manifold3d, Trueform, Meshlib):
        if cls.name in names:
            try:
                libs.append(cls())
            except ImportError as e:
                print(f"<!-- {cls.name} not available: {e} -->", file=sys.stderr)
    return libs


def table(names, records):
    """Prints the table and the volume identities of a run's records. A peer's result
    counts for the fastest peer only when it has triangles where meshbool's has (an
    empty result is a refusal: manifold3d on open surfaces). Two ratios, each ours over
    the fastest peer's: the boolean calls alone, and numpy in -> numpy out."""
    peers = [n for n in names if not n.startswith("meshbool")]
    rows = {}
    for r in records:
        if "op" in r:
            rows.setdefault((r["case"], r["op"]), {})[r["lib"]] = r
    print("| case | op | " + " | ".join(f"{n} core / numpy (ms)" for n in names)
          + " | meshbool ÷ fastest peer: core | : numpy |")
    print("|---" * (len(names) + 4) + "|")
    for (case, op), row in rows.items():
        ours = row.get("meshbool")
        usable = lambda r: "core" in r and (r["triangles"] > 0 or not ours or ours.get("triangles", 0) == 0)
        cells = []
        for n in names:
            r = row.get(n)
            if r is None or "core" not in r:
                cells.append("fails")
            else:
                cell = f"{r['core'] * 1e3:.1f} / {r['numpy'] * 1e3:.1f}"
                cells.append(cell if usable(r) else cell + " (empty)")
        ok = [row[n] for n in peers if n in row and usable(row[n])]
        ratio = lambda key: (f"{ours['core'] / min(r[key] for r in ok):.2f}"
                             if ok and ours and "core" in ours else "–")
        print(f"| {case} | {op} | " + " | ".join(cells) + f" | {ratio('core')} | {ratio('numpy')} |")
    ident = [r for r in records if "identity_error" in r]
    print()
    print("Volume identity error |vol(A∪B)+vol(A∩B)−vol(A)−vol(B)| / (vol(A)+vol(B)):")
    for r in ident:
        print(f"- {r['case']} {r['lib']}: {r['identity_error']:.1e}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("meshes", help="directory written by gen_meshes.py (with cases.json)")
    ap.add_argument("--cases", default="sphere_5k,sphere_500k,sphere_2m,cube_coplanar_g16,cube_identical_g16")
    ap.add_argument("--libs", default="manifold3d,trueform,meshlib")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--json", help="also write every measurement to this file")
    ap.add_argument("--real", help="directory of the real model pairs (../shared/data/real): adds "
                    "the cases thingi_79741_65004 and thingi_908460_73416 (name them in --cases)")
    ap.add_argument("--table", action="store_true",
                    help="print the table of the records in MESHES (a --json file) instead of running")
    args = ap.parse_args()
    if args.table:
        records = json.load(open(args.meshes))
        names = list(dict.fromkeys(r["lib"] for r in records))
        table(names, records)
        return
    cases = json.load(open(f"{args.meshes}/cases.json"))
    if args.real:
        # Absolute: the cases' paths are read relative to MESHES.
        real = os.path.abspath(args.real)
        for a, b in (("79741", "65004"), ("908460", "73416")):
            cases[f"thingi_{a}_{b}"] = {"A": os.path.join(real, f"thingi_{a}.obj"),
                                        "B": os.path.join(real, f"thingi_{b}.obj")}
    libs = libraries(args.libs.split(","))
    records = []
    for case in args.cases.split(","):
        c = cases[case]
        a = meshbool.read(os.path.join(args.meshes, c["A"]))
        b = meshbool.read(os.path.join(args.meshes, c["B"]))
        reps = max(1, args.reps if len(a.faces) < 1_000_000 else (args.reps + 1) // 2)
        vols = {}
        for op in OPS:
            for lib in libs:
                try:
                    pa, pb = lib.prepare(a.vertices, a.faces), lib.prepare(b.vertices, b.faces)
                    core, r = median_time(lambda: lib.boolean(pa, pb, op), reps)

                    def whole():
                        x = lib.boolean(lib.prepare(a.vertices, a.faces), lib.prepare(b.vertices, b.faces), op)
                        return lib.extract(x)

                    full, (v, f) = median_time(whole, reps)
                    vol = volume(v, f)
                    vols.setdefault(op, {})[lib.name] = vol
                    records.append({"case": case, "op": op, "lib": lib.name, "core": core, "numpy": full,
                                    "triangles": int(len(f)), "volume": vol})
                except Exception as e:  # a library refusing a case is a result too
                    records.append({"case": case, "op": op, "lib": lib.name, "error": str(e)[:200]})
        # Inclusion-exclusion per library: vol(A∪B) + vol(A∩B) = vol(A) + vol(B).
        va, vb = volume(a.vertices, a.faces), volume(b.vertices, b.faces)
        for lib in libs:
            try:
                err = abs(vols["union"][lib.name] + vols["intersection"][lib.name] - va - vb) / (va + vb)
                records.append({"case": case, "lib": lib.name, "identity_error": err})
            except KeyError:
                pass
    table([lib.name for lib in libs], records)
    if args.json:
        json.dump(records, open(args.json, "w"), indent=1)


if __name__ == "__main__":
    main()
