#!/usr/bin/env python3
"""Booleans on the real models, in process, against the peers: time and peak memory.

Every closed model of ``../shared/data/corpus`` (its manifest says which) and every model of
``../shared/data/real`` meets two partners: its own copy turned by 17 degrees about a skew axis
through its box's centre (and moved by 1 % of the diagonal), and an icosphere of 5,120
triangles centred off the box's centre. Each pair runs the three operations, so a case is
(model, partner, operation).

Each case runs once per library in a child process of its own, which reports its time and
its peak resident memory (``ru_maxrss``) above what the process held after importing the
library, reading the two meshes and one boolean of two small spheres (so that what a library
sets up once per process is not counted). Columns, medians over the repetitions, all in one child:

- meshbool: *default* -- ``meshbool.boolean((v, f), (v, f), op)`` from arrays with every
  default (weld, self-intersection check, resolve), result arrays out; *unchecked* -- the
  same with ``self_check=False``; *core* -- the call alone on ``Operand``s built with
  ``self_check=False`` before the timer.
- each peer: *arrays* -- its objects built from the arrays, the call, the result's arrays
  out; *core* -- the call alone on objects built before the timer.

Ratios are meshbool's over the fastest peer whose result is usable (not an error, and not
empty where meshbool's is not): default and unchecked over the fastest peer's *arrays*,
core over the fastest peer's *core*. Memory: meshbool's peak (the default path dominates it)
over manifold3d's.

    python3 -m venv /tmp/bv && /tmp/bv/bin/pip install numpy manifold3d trueform ./crates/meshbool-py
    /tmp/bv/bin/python bench/corpus_inprocess.py --json corpus.json
    /tmp/bv/bin/python bench/corpus_inprocess.py --table corpus.json
"""

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys

import numpy as np

# The peers' adapters, the volume and the median timer of the generated meshes' benchmark.
from inprocess import Manifold3d, Trueform, volume
from inprocess import median_time as timed

OPS = ("union", "intersection", "difference")
HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "data"))


def icosphere(level):
    t = (1 + 5**0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    v = [np.array(p, dtype=float) / np.linalg.norm(p) for p in v]
    for _ in range(level):
        mid, nf = {}, []

        def m(i, j):
            k = (min(i, j), max(i, j))
            if k not in mid:
                p = v[i] + v[j]
                v.append(p / np.linalg.norm(p))
                mid[k] = len(v) - 1
            return mid[k]

        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return np.array(v), np.array(f, dtype=np.uint32)


def partner(v, kind):
    """The second operand of a case: ``rotated`` or ``sphere``."""
    lo, hi = v.min(axis=0), v.max(axis=0)
    c, d = (lo + hi) / 2, float(np.linalg.norm(hi - lo))
    if kind == "rotated":
        axis = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
        a = np.radians(17.0)
        k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
        r = np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * (k @ k)
        return (v - c) @ r.T + c + 0.01 * d, None
    sv, sf = icosphere(4)
    return sv * (0.3 * d) + c + np.array([0.11, 0.07, 0.05]) * d, sf


def models(corpus, real):
    out = []
    manifest = json.load(open(os.path.join(corpus, "manifest.json")))
    out += [os.path.join(corpus, m["file"]) for m in manifest if m["closed"]]
    out += sorted(os.path.join(real, n) for n in os.listdir(real) if n.endswith(".obj"))
    return out


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def child(args):
    """One case and one library in this process; prints one JSON record."""
    lib, model, kind, op, reps = args.child
    reps = int(reps)
    import meshbool

    a = meshbool.read(model)
    av, af = np.ascontiguousarray(a.vertices, dtype=np.float64), np.ascontiguousarray(a.faces)
    bv, bf = partner(av, kind)
    bf = af if bf is None else bf
    rec = {"model": os.path.basename(model), "partner": kind, "op": op, "lib": lib,
           "triangles_in": int(len(af) + len(bf))}
    # One boolean of two small spheres first, so that what a library sets up once per process
    # (thread pools, tables) is not counted as the case's memory.
    wv, wf = icosphere(1)
    warm = (wv, wf), (wv * 0.8 + 0.3, wf)
    if lib == "meshbool":
        meshbool.boolean(*warm, op)
        base = peak_mb()
        rec["default"], r = timed(lambda: meshbool.boolean((av, af), (bv, bf), op), reps)
        rec["triangles"], rec["volume"] = int(len(r.faces)), volume(r.vertices, r.faces)
        rec["peak_mb"] = peak_mb() - base
        rec["unchecked"], _ = timed(
            lambda: meshbool.boolean((av, af), (bv, bf), op, self_check=False), reps)
        pa = meshbool.Operand((av, af), self_check=False)
        pb = meshbool.Operand((bv, bf), self_check=False)
        rec["core"], _ = timed(lambda: meshbool.boolean(pa, pb, op, self_check=False), reps)
    else:
        peer = {"manifold3d": Manifold3d, "trueform": Trueform}[lib]()

        def arrays():
            x, y = peer.prepare(av, af), peer.prepare(bv, bf)
            return peer.extract(peer.boolean(x, y, op))

        peer.extract(peer.boolean(peer.prepare(*warm[0]), peer.prepare(*warm[1]), op))
        base = peak_mb()
        rec["arrays"], (v, f) = timed(arrays, reps)
        rec["peak_mb"] = peak_mb() - base
        x, y = peer.prepare(av, af), peer.prepare(bv, bf)
        rec["core"], _ = timed(lambda: peer.boolean(x, y, op), reps)
        rec["triangles"], rec["volume"] = int(len(f)), volume(v, f)
    print(json.dumps(rec))


def run(args):
    records = []
    if args.json and os.path.exists(args.json) and args.resume:
        records = json.load(open(args.json))
    done = {(r["model"], r["partner"], r["op"], r["lib"]) for r in records}
    todo = models(args.corpus, args.real)
    if args.models:
        keep = args.models.split(",")
        todo = [m for m in todo if any(k in os.path.basename(m) for k in keep)]
    for model in todo:
        import meshbool

        n = len(meshbool.read(model).faces)
        reps = args.reps if n < 100_000 else max(1, args.reps // 2)
        for kind in ("rotated", "sphere"):
            for op in OPS:
                for lib in args.libs.split(","):
                    key = (os.path.basename(model), kind, op, lib)
                    if key in done:
                        continue
                    cmd = [sys.executable, __file__, "--child", lib, model, kind, op, str(reps)]
                    try:
                        p = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
                        if p.returncode == 0:
                            rec = json.loads(p.stdout.strip().splitlines()[-1])
                        else:
                            err = (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
                    except subprocess.TimeoutExpired:
                        p, err = None, f"over {args.timeout} s"
                    if p is None or p.returncode != 0:
                        rec = {"model": key[0], "partner": kind, "op": op, "lib": lib,
                               "error": err[:200]}
                    records.append(rec)
                    print(json.dumps(rec), file=sys.stderr, flush=True)
                    if args.json:
                        json.dump(records, open(args.json, "w"), indent=0)
    return records


def table(records):
    rows = {}
    for r in records:
        rows.setdefault((r["model"], r["partner"], r["op"]), {})[r["lib"]] = r
    peers = sorted({r["lib"] for r in records} - {"meshbool"})
    print("| model | partner | op | meshbool default / unchecked / core (ms) | "
          + " | ".join(f"{p} arrays / core (ms)" for p in peers)
          + " | default ÷ peer | unchecked ÷ peer | core ÷ peer | meshbool / manifold3d peak (MB) |")
    print("|---" * (len(peers) + 8) + "|")
    ratios = {"default": [], "unchecked": [], "core": []}
    mem = []
    for (model, kind, op), row in rows.items():
        ours = row.get("meshbool", {})
        usable = [row[p] for p in peers if p in row and "arrays" in row[p]
                  and (row[p]["triangles"] > 0 or ours.get("triangles", 0) == 0)]
        cells = []
        if "default" in ours:
            cells.append(f"{ours['default'] * 1e3:.1f} / {ours['unchecked'] * 1e3:.1f} / {ours['core'] * 1e3:.1f}")
        else:
            cells.append("fails: " + ours.get("error", "?")[:60])
        for p in peers:
            r = row.get(p, {})
            if "arrays" in r:
                empty = " (empty)" if r["triangles"] == 0 and ours.get("triangles", 0) > 0 else ""
                cells.append(f"{r['arrays'] * 1e3:.1f} / {r['core'] * 1e3:.1f}{empty}")
            else:
                cells.append("fails")
        rs = []
        for key, peer_key in (("default", "arrays"), ("unchecked", "arrays"), ("core", "core")):
            if usable and key in ours:
                x = ours[key] / min(r[peer_key] for r in usable)
                ratios[key].append((x, f"{model} {kind} {op}"))
                rs.append(f"{x:.2f}")
            else:
                rs.append("–")
        m = row.get("manifold3d", {})
        if "peak_mb" in ours and "peak_mb" in m:
            mm = f"{ours['peak_mb']:.1f} / {m['peak_mb']:.1f}"
            if m.get("triangles", 0) > 0:
                mem.append((ours["peak_mb"] / max(m["peak_mb"], 1.0), f"{model} {kind} {op}"))
        else:
            mm = "–"
        print(f"| {model} | {kind} | {op} | " + " | ".join(cells) + " | " + " | ".join(rs) + f" | {mm} |")
    print()
    for key, xs in ratios.items():
        if not xs:
            continue
        v = sorted(x for x, _ in xs)
        worst = max(xs)
        print(f"- {key} ÷ fastest peer over {len(v)} cases: median {statistics.median(v):.2f}, "
              f"p90 {v[int(0.9 * (len(v) - 1))]:.2f}, worst {worst[0]:.2f} ({worst[1]}); "
              f"{sum(x > 1 for x in v)} above 1")
    if mem:
        v = sorted(x for x, _ in mem)
        worst = max(mem)
        print(f"- peak memory ÷ manifold3d's (each at least 1 MB) over {len(v)} cases: median "
              f"{statistics.median(v):.2f}, worst {worst[0]:.2f} ({worst[1]}); {sum(x > 1.5 for x in v)} above 1.5")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--corpus", default=os.path.join(SHARED, "corpus"))
    ap.add_argument("--real", default=os.path.join(SHARED, "real"))
    ap.add_argument("--libs", default="meshbool,manifold3d,trueform")
    ap.add_argument("--models", help="only the models whose file names contain one of these (comma-separated)")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--timeout", type=int, default=300, help="seconds per child")
    ap.add_argument("--json", help="write the records here (after every case)")
    ap.add_argument("--resume", action="store_true", help="keep the records in --json and run the rest")
    ap.add_argument("--table", metavar="JSON", help="print the table of a --json file instead of running")
    ap.add_argument("--child", nargs=5, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args)
    elif args.table:
        table(json.load(open(args.table)))
    else:
        table(run(args))


if __name__ == "__main__":
    main()
