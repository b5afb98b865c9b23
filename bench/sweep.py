#!/usr/bin/env python3
"""The corpus sweep: every mesh of ../shared/data/corpus and ../shared/data/real through the
`meshbool` command line with default options, as a user meets it.

Each model A is taken against three partners B, for union, intersection and difference:
- `rot`: A rotated 17 degrees about the axis (1, 2, 3) through its box centre and moved by
  (0.07, -0.05, 0.03) x its box diagonal;
- `sphere`: an icosphere of 1,280 triangles, radius 0.3 x the diagonal, its centre the box
  centre moved by 0.05 x the diagonal along (1, 1, 1);
- `next`: the next model of the corpus in name order (the last takes the first).

Each run records: answered or refused (the reason), the result's triangles, boundary and
non-manifold edges, closed, volume, wall time and peak resident memory (of the child
process), and the operands' volumes as they entered the boolean (the report's
`operands[].volume`: after orientation and resolve at the door). For every pair whose
three runs were answered it checks the identities
    vol(A u B) + vol(A n B) = vol(A') + vol(B')   and   vol(A - B) + vol(A n B) = vol(A')
relative to max(|vol(A')|, |vol(B')|). With --manifold, manifold3d (Python package) runs
the same pairs on the operands as meshbool reads them (exactly welded) and its volume and
time are recorded beside ours.

    cargo build --release -p meshbool-cli
    python3 bench/sweep.py --json sweep.json --markdown sweep.md          # whole sweep
    python3 -m venv /tmp/sv && /tmp/sv/bin/pip install numpy manifold3d
    /tmp/sv/bin/python bench/sweep.py --manifold --json sweep.json --markdown sweep.md
    python3 bench/sweep.py --quick --expect bench/sweep_expected.json     # CI's gate

--expect FILE compares the sweep with the outcomes FILE lists (`"model partner op":
"closed" | "open" | "refused"`): a run listed as closed must answer with a closed,
manifold result, and every pair listed must satisfy the identities; the sweep fails
(exit 1) when one does not. --write-expect FILE writes the current outcomes.
"""

import argparse
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import time

OPS = ("union", "intersection", "difference")
PARTNERS = ("rot", "sphere", "next")
# The identities' tolerance, relative to the larger operand volume (see `identities`).
IDENTITY_TOL = 1e-9
# Models of the quick sweep (small and quick, one of each kind of trouble).
QUICK = (
    "broken_back_to_back.stl",
    "broken_box_overlapping.stl",
    "broken_capsule_poles.obj",
    "broken_cubes_touching.stl",
    "broken_utm_block_a.off",
    "cad_adns2610_case.stl",
    "cad_featuretype.stl",
    "cad_gears.stl",
    "cad_plate_holes.stl",
    "open_fault_santa_monica.obj",
    "open_terrain_grid.off",
    "print_far_out_ring.stl",
    "print_hourglass.stl",
    "print_pcbvicebar.stl",
    "print_xyz_cube.stl",
    "scan_horse_inverted.ply",
    "scan_knot.obj",
)


def icosphere(subdivisions=3):
    """Unit icosphere: 20 * 4^subdivisions triangles, facing outward."""
    t = (1.0 + 5.0**0.5) / 2.0
    verts = [
        (-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
        (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
        (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1),
    ]  # fmt: skip
    faces = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]  # fmt: skip
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    for _ in range(subdivisions):
        middle = {}

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in middle:
                p = [(a + b) / 2 for a, b in zip(verts[i], verts[j])]
                n = math.sqrt(sum(x * x for x in p))
                verts.append(tuple(x / n for x in p))
                middle[key] = len(verts) - 1
            return middle[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return verts, faces


def write_ply(path, verts, faces):
    with open(path, "wb") as f:
        f.write(
            (
                "ply\nformat binary_little_endian 1.0\n"
                f"element vertex {len(verts)}\n"
                "property double x\nproperty double y\nproperty double z\n"
                f"element face {len(faces)}\n"
                "property list uchar int vertex_indices\nend_header\n"
            ).encode()
        )
        f.write(b"".join(struct.pack("<3d", *v) for v in verts))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in faces))


def read_ply(path):
    """Reads the binary little-endian double PLY that `meshbool convert` writes."""
    import numpy as np

    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    nv = int(next(h for h in header if h.startswith("element vertex")).split()[2])
    nf = int(next(h for h in header if h.startswith("element face")).split()[2])
    v = np.frombuffer(data, dtype="<f8", count=3 * nv, offset=end).reshape(nv, 3)
    f = np.frombuffer(
        data, dtype=np.dtype([("n", "u1"), ("i", "<i4", (3,))]), count=nf, offset=end + 24 * nv
    )
    return v.copy(), f["i"].astype(np.uint64)


def run(cmd, timeout):
    """Runs `cmd`; returns (exit code or 'timeout', stdout, stderr, seconds, peak MiB)."""
    start = time.perf_counter()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err)
        deadline = start + timeout
        status = None
        while True:
            pid, st, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                status = os.waitstatus_to_exitcode(st)
                break
            if time.perf_counter() > deadline:
                p.kill()
                _, _, usage = os.wait4(p.pid, 0)
                status = "timeout"
                break
            time.sleep(0.002)
        p.returncode = 0  # reaped above
        seconds = time.perf_counter() - start
        out.seek(0)
        err.seek(0)
        return status, out.read().decode(), err.read().decode(), seconds, usage.ru_maxrss / 1024


def info(binary, path):
    status, out, err, _, _ = run([binary, "info", path, "--json"], 120)
    if status != 0:
        return None, (err.strip().splitlines() or ["no message"])[-1]
    return json.loads(out), None


def make_partners(binary, model, inf, work):
    """Writes the `rot` and `sphere` partners of `model` into `work`."""
    lo, hi = inf["bbox"]["min"], inf["bbox"]["max"]
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    diag = math.dist(lo, hi)
    base = os.path.join(work, os.path.basename(model))
    rot = base + ".rot.ply"
    shift = [c[0] + 0.07 * diag, c[1] - 0.05 * diag, c[2] + 0.03 * diag]
    status, _, err, _, _ = run(
        [binary, "transform", model, "-o", rot]
        + ["--translate", ",".join(repr(-x) for x in c)]
        + ["--rotate", "1,2,3,17"]
        + ["--translate", ",".join(repr(x) for x in shift)],
        120,
    )
    if status != 0:
        print(f"{os.path.basename(model)}: no rotated copy: {err.strip()}", file=sys.stderr)
        rot = None
    verts, faces = icosphere(3)
    r = 0.3 * diag
    s = 0.05 * diag / math.sqrt(3)
    centre = [x + s for x in c]
    sphere = base + ".sphere.ply"
    write_ply(sphere, [tuple(centre[k] + r * v[k] for k in range(3)) for v in verts], faces)
    return {"rot": rot, "sphere": sphere}


def boolean(binary, op, a, b, work, timeout):
    out = os.path.join(work, "result.ply")
    status, stdout, stderr, seconds, peak = run(
        [binary, op, a, b, "-o", out, "--json"], timeout
    )
    rec = {"seconds": round(seconds, 4), "peak_mib": round(peak, 1)}
    if status == "timeout":
        rec.update(status="timeout")
    elif status != 0:
        lines = [line for line in stderr.strip().splitlines() if line.strip()]
        rec.update(status="refused" if status == 1 else f"exit {status}",
                   reason=lines[0] if lines else "no message")  # fmt: skip
    else:
        r = json.loads(stdout)
        rec.update(
            status="answered",
            triangles=r["triangles"],
            boundary_edges=r["boundary_edges"],
            non_manifold_edges=r["non_manifold_edges"],
            closed=r["closed"] or r["triangles"] == 0,
            empty=r["triangles"] == 0,
            volume=r["volume"],
            operand_volumes=[o.get("volume") for o in r["operands"]],
            # Operands the door closed by merging positions that differ by rounding.
            closed_by_noise=[
                (o.get("rounding_noise") or {}).get("boundary_edges", [1, 1])[1] == 0
                for o in r["operands"]
            ],
            # Operands the door resolved: closed, or non-manifold with every edge used
            # as often in each direction (the resolve takes nothing else).
            closed_by_resolve=[o.get("resolved") is not None for o in r["operands"]],
            assumed=len(r.get("assumed", [])),
        )
    return rec


def closed_operands(a_info, b_info, runs):
    """Whether both operands are closed: as read (exactly welded), once the door merged
    positions that differ by rounding (the report's `rounding_noise`), or as the door
    resolved them (closed, or non-manifold with every edge used as often in each
    direction: the report's `resolved`)."""
    answered = [r for r in runs.values() if r["status"] == "answered"]
    noise = next((r["closed_by_noise"] for r in answered), [False, False])
    resolved = next((r["closed_by_resolve"] for r in answered), [False, False])
    a = bool(a_info and a_info["closed"]) or noise[0] or resolved[0]
    b = bool(b_info and b_info["closed"]) or noise[1] or resolved[1]
    return a and b


def spread(a, b):
    """(Diagonal of the box around both meshes' boxes / the larger one's diagonal)^2."""
    if not (a and b and a.get("bbox") and b.get("bbox")):
        return 1.0
    lo = [min(x, y) for x, y in zip(a["bbox"]["min"], b["bbox"]["min"])]
    hi = [max(x, y) for x, y in zip(a["bbox"]["max"], b["bbox"]["max"])]
    larger = max(math.dist(a["bbox"]["min"], a["bbox"]["max"]), math.dist(b["bbox"]["min"], b["bbox"]["max"]))
    return (math.dist(lo, hi) / larger) ** 2 if larger > 0 else 1.0


def manifold_runs(a_ply, b_ply):
    """manifold3d on the two operands: {op: (volume or None, seconds)}, or an error."""
    import manifold3d as m3

    out = {}
    try:
        va, fa = read_ply(a_ply)
        vb, fb = read_ply(b_ply)
        start = time.perf_counter()
        a = m3.Manifold(m3.Mesh64(va, fa))
        b = m3.Manifold(m3.Mesh64(vb, fb))
        build = time.perf_counter() - start
        if a.status() != m3.Error.NoError or b.status() != m3.Error.NoError:
            return {"refused": f"{a.status()} / {b.status()}"}
        for op in OPS:
            start = time.perf_counter()
            r = {"union": lambda: a + b, "intersection": lambda: a ^ b,
                 "difference": lambda: a - b}[op]()  # fmt: skip
            r.num_tri()
            out[op] = {"volume": r.volume(), "seconds": round(time.perf_counter() - start + build, 4)}
    except Exception as e:  # noqa: BLE001 - any failure of the peer is recorded
        return {"refused": str(e)[:200]}
    return out


def identities(runs, spread=1.0):
    """Errors of the two identities for one pair's three runs, or None: relative to the
    larger operand volume, and divided by `spread`, the square of the box around both
    operands' diagonal over the larger operand's. A volume is summed from triple
    products of coordinates taken about the result's box centre, whose rounding grows
    with the square of the distance from it: for operands far apart (a UTM block and a
    part at the origin) the result's volume is rounded at the pair's scale, not the
    operands'. For operands that overlap, spread is 1 to 4."""
    if any(runs.get(op, {}).get("status") != "answered" for op in OPS):
        return None
    va, vb = runs["union"]["operand_volumes"]
    scale = max(abs(va), abs(vb), 1e-300) * max(spread, 1.0)
    u, i, d = (runs[op]["volume"] for op in OPS)
    return {
        "union_intersection": abs(u + i - va - vb) / scale,
        "difference_intersection": abs(d + i - va) / scale,
    }


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(root, "target", "release", "meshbool"))
    ap.add_argument("--data", default=os.path.join(os.path.dirname(root), "shared", "data"))
    ap.add_argument("--quick", action="store_true", help="the quick models only (CI)")
    ap.add_argument("--only", help="comma-separated model names")
    ap.add_argument("--partners", default=",".join(PARTNERS))
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--manifold", action="store_true", help="also run manifold3d")
    ap.add_argument("--json", help="write every record here")
    ap.add_argument("--markdown", help="write the tables here")
    ap.add_argument("--expect", help="fail where a listed outcome is not met")
    ap.add_argument("--write-expect", help="write the outcomes here")
    args = ap.parse_args()

    corpus = os.path.join(args.data, "corpus")
    real = os.path.join(args.data, "real")
    if not os.path.isdir(corpus):
        print(f"sweep: no corpus at {corpus}: skipped", file=sys.stderr)
        return 0
    names = sorted(n for n in os.listdir(corpus) if n.split(".")[-1] in ("stl", "obj", "ply", "off"))
    models = [os.path.join(corpus, n) for n in names]
    if os.path.isdir(real):
        models += [os.path.join(real, n) for n in sorted(os.listdir(real)) if n.endswith(".obj")]
    ring = [m for m in models if m.startswith(corpus)]
    nxt = {m: ring[(k + 1) % len(ring)] for k, m in enumerate(ring)}
    wanted = set(QUICK) if args.quick else None
    if args.only:
        wanted = set(args.only.split(","))
    if wanted is not None:
        models = [m for m in models if os.path.basename(m) in wanted]
    partners = args.partners.split(",")

    records = []
    with tempfile.TemporaryDirectory() as work:
        for model in models:
            name = os.path.basename(model)
            inf, why = info(args.bin, model)
            if inf is None:
                records.append({"model": name, "partner": None, "status": "unreadable", "reason": why})
                print(f"{name}: unreadable: {why}", file=sys.stderr)
                continue
            made = make_partners(args.bin, model, inf, work)
            made["next"] = nxt.get(model)
            a_ply = os.path.join(work, "a.ply")
            a_converted = args.manifold and run([args.bin, "convert", model, a_ply], 120)[0] == 0
            for partner in partners:
                b = made.get(partner)
                if b is None:
                    continue
                b_inf = info(args.bin, b)[0]
                runs = {op: boolean(args.bin, op, model, b, work, args.timeout) for op in OPS}
                rec = {
                    "model": name,
                    "partner": partner if partner != "next" else f"next:{os.path.basename(b)}",
                    "triangles": inf["triangles"],
                    "closed_operands": closed_operands(inf, b_inf, runs),
                    "runs": runs,
                    "identities": identities(runs, spread(inf, b_inf)),
                }
                if args.manifold:
                    b_ply = os.path.join(work, "b.ply")
                    ok = a_converted and run([args.bin, "convert", b, b_ply], 120)[0] == 0
                    rec["manifold3d"] = manifold_runs(a_ply, b_ply) if ok else {"refused": "convert"}
                records.append(rec)
                print(summary_line(rec), file=sys.stderr, flush=True)

    if args.json:
        with open(args.json, "w") as f:
            json.dump(records, f, indent=1)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(markdown(records, args))
    if args.write_expect:
        with open(args.write_expect, "w") as f:
            json.dump(outcomes(records), f, indent=1, sort_keys=True)
            f.write("\n")
    totals = totals_of(records)
    print(" ".join(f"{k}={v}" for k, v in totals.items()), file=sys.stderr)
    if args.expect:
        failures = check(records, json.load(open(args.expect)))
        for line in failures:
            print(f"FAIL {line}")
        ran = sum(len(r["runs"]) for r in records if "runs" in r)
        print(f"{ran - len(failures)} passed, {len(failures)} failed")
        return 1 if failures else 0
    return 0


def outcome(run):
    if run["status"] != "answered":
        return "refused"
    return "closed" if run["closed"] and run["non_manifold_edges"] == 0 else "open"


def outcomes(records):
    out = {}
    for rec in records:
        for op, r in rec.get("runs", {}).items():
            out[f"{rec['model']} {rec['partner']} {op}"] = outcome(r)
    return out


def check(records, expected):
    """Where the sweep falls short of the expected outcomes (one line each)."""
    failures = []
    for rec in records:
        for op, r in rec.get("runs", {}).items():
            key = f"{rec['model']} {rec['partner']} {op}"
            want = expected.get(key)
            got = outcome(r)
            if want == "closed" and got != "closed":
                detail = r.get("reason") or f"{r.get('boundary_edges')} boundary, {r.get('non_manifold_edges')} non-manifold edges"
                failures.append(f"{key}: expected closed, got {got} ({detail})")
            elif want == "open" and got == "refused":
                failures.append(f"{key}: expected an answer, got refused ({r.get('reason')})")
        ids = rec.get("identities")
        key = f"{rec['model']} {rec['partner']} union"
        if expected.get(key) == "closed" and rec.get("closed_operands"):
            if ids is None:
                failures.append(f"{rec['model']} {rec['partner']}: identities not checked (a run was refused)")
            else:
                for k, e in ids.items():
                    if e > IDENTITY_TOL:
                        failures.append(f"{rec['model']} {rec['partner']}: identity {k} off by {e:.2e}")
    return failures


def totals_of(records):
    runs = [r for rec in records for r in rec.get("runs", {}).values()]
    closed_in = [r for rec in records if rec.get("closed_operands") for r in rec["runs"].values()]
    ids = [rec["identities"] for rec in records if rec.get("identities") and rec.get("closed_operands")]
    return {
        "models": len({rec["model"] for rec in records}),
        "unreadable": sum(1 for rec in records if rec.get("status") == "unreadable"),
        "runs": len(runs),
        "answered": sum(1 for r in runs if r["status"] == "answered"),
        "refused": sum(1 for r in runs if r["status"] != "answered"),
        "closed_in_runs": len(closed_in),
        "closed_in_closed_out": sum(1 for r in closed_in if outcome(r) == "closed"),
        "identity_pairs": len(ids),
        "identity_failures": sum(1 for i in ids if max(i.values()) > IDENTITY_TOL),
    }


def summary_line(rec):
    parts = []
    for op, r in rec["runs"].items():
        if r["status"] == "answered":
            flag = "closed" if outcome(r) == "closed" else f"OPEN b{r['boundary_edges']} n{r['non_manifold_edges']}"
            parts.append(f"{op[:5]} {flag} {r['seconds']:.2f}s")
        else:
            parts.append(f"{op[:5]} {r['status'].upper()}")
    ids = rec.get("identities")
    idt = f" id {max(ids.values()):.1e}" if ids else ""
    return f"{rec['model']} × {rec['partner']}: " + ", ".join(parts) + idt


def fmt_volume(v):
    return "" if v is None else f"{v:.6g}"


def cell(r):
    """One run in a table cell."""
    if r["status"] != "answered":
        return r["status"]
    o = outcome(r)
    if r["empty"]:
        return "closed (empty)"
    return o if o == "closed" else f"open ({r['boundary_edges']} / {r['non_manifold_edges']})"


def manifold_cell(rec):
    """manifold3d's agreement with meshbool's volumes, and its time, for one pair."""
    m = rec.get("manifold3d")
    if m is None:
        return ""
    if "refused" in m:
        return "refused"
    diffs = []
    for op in OPS:
        r = rec["runs"][op]
        if op in m and r["status"] == "answered" and m[op]["volume"] is not None:
            scale = max(abs(v) for v in r["operand_volumes"]) or 1.0
            diffs.append(abs(m[op]["volume"] - r["volume"]) / scale)
    worst = f"{max(diffs):.0e}" if diffs else "-"
    seconds = "/".join(f"{m[op]['seconds']:.3f}" for op in OPS if op in m)
    return f"{worst}, {seconds} s"


def markdown(records, args):
    t = totals_of(records)
    lines = [
        "| | count |",
        "|---|---|",
        f"| models | {t['models']} ({t['unreadable']} unreadable) |",
        f"| runs | {t['runs']} |",
        f"| answered | {t['answered']} |",
        f"| refused | {t['refused']} |",
        f"| runs with closed operands | {t['closed_in_runs']} |",
        f"| · closed, manifold result | {t['closed_in_closed_out']} |",
        f"| pairs of closed operands with the identities checked | {t['identity_pairs']} |",
        f"| · off by more than {IDENTITY_TOL:g} | {t['identity_failures']} |",
        "",
        "Per pair: each operation's outcome (open: boundary / non-manifold edges), the larger",
        "identity error (closed operands), wall time of the three runs, peak resident memory",
        "of the largest"
        + (", and manifold3d's largest volume difference relative to the larger operand"
           " volume, with its times (building its operands included)." if args.manifold else "."),
        "",
        "| model | partner | closed in | union | intersection | difference | identity | s | MiB |"
        + (" manifold3d |" if args.manifold else ""),
        "|---|---|---|---|---|---|---|---|---|" + ("---|" if args.manifold else ""),
    ]  # fmt: skip
    reasons = {}
    for rec in records:
        if rec.get("status") == "unreadable":
            lines.append(f"| {rec['model']} | | | unreadable | | | | | |" + (" |" if args.manifold else ""))
            reasons.setdefault(rec["model"], rec["reason"])
            continue
        runs = rec["runs"]
        ids = rec.get("identities")
        idt = f"{max(ids.values()):.0e}" if ids and rec["closed_operands"] else ""
        secs = "/".join(f"{runs[op]['seconds']:.2f}" for op in OPS)
        peak = max(runs[op]["peak_mib"] for op in OPS)
        row = (
            f"| {rec['model']} | {rec['partner']} | {'yes' if rec['closed_operands'] else 'no'} | "
            + " | ".join(cell(runs[op]) for op in OPS)
            + f" | {idt} | {secs} | {peak:.0f} |"
        )
        if args.manifold:
            row += f" {manifold_cell(rec)} |"
        lines.append(row)
        for op in OPS:
            if runs[op]["status"] != "answered":
                reasons.setdefault(rec["model"], runs[op].get("reason", ""))
    if reasons:
        lines += ["", "Why runs were refused (the first refusal of each model):", ""]
        for model, why in reasons.items():
            why = why.replace("|", "/")
            lines.append(f"- `{model}`: {why[:300]}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
