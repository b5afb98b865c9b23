"""The Python package end to end: every function, geometry asserted (volumes, identities,
closedness, counts), and bad input raising the right exception."""

import inspect
import json
import math
import pathlib

import numpy as np
import pytest

import meshbool

#: Other projects' data beside the checkout (the Kirra surfaces of the reference JS
#: library), kept out of the repository: the tests of its figures are skipped without it.
SHARED = pathlib.Path(__file__).resolve().parents[4] / "shared" / "data"
needs_shared_data = pytest.mark.skipif(not SHARED.is_dir(), reason="../shared/data not found")


def uv_sphere(center, radius, segments, rings):
    """A closed UV sphere facing outward: poles plus (rings - 1) rings of vertices."""
    verts = [[0.0, 0.0, radius], [0.0, 0.0, -radius]]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            verts.append(
                [
                    radius * math.sin(theta) * math.cos(phi),
                    radius * math.sin(theta) * math.sin(phi),
                    radius * math.cos(theta),
                ]
            )
    faces = []
    ring = lambda i, j: 2 + (i - 1) * segments + (j % segments)  # noqa: E731
    for j in range(segments):
        faces.append([0, ring(1, j), ring(1, j + 1)])
        faces.append([1, ring(rings - 1, j + 1), ring(rings - 1, j)])
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j), ring(i + 1, j + 1)
            faces.append([a, c, b])
            faces.append([b, c, d])
    return np.array(verts) + np.asarray(center, dtype=float), np.array(faces)


def test_mesh_holds_arrays_and_measures():
    m = meshbool.box([0, 0, 0], [2, 1, 1])
    assert m.vertices.dtype == np.float64 and m.vertices.shape == (8, 3)
    assert m.faces.dtype == np.uint32 and m.faces.shape == (12, 3)
    assert m.volume == 2.0 and m.area == 10.0 and m.is_closed
    s = m.stats()
    assert s["schema"] == meshbool.SCHEMA
    assert (s["triangles"], s["boundary_edges"], s["components"]) == (12, 0, 1)
    assert s["bbox"] == {"min": [0.0, 0.0, 0.0], "max": [2.0, 1.0, 1.0]}
    assert "file" not in s
    assert repr(m) == "meshbool.Mesh(8 vertices, 12 faces)"
    # Any integer and float dtypes are taken.
    m2 = meshbool.Mesh(m.vertices.astype(np.float32), m.faces.astype(np.int64))
    assert m2.volume == 2.0


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (np.zeros((3, 3)), [[0, 1, 3]], "out of range"),
        (np.zeros((3, 3)), [[0, 1, -1]], "must be in"),
        (np.zeros((3, 2)), [[0, 1, 2]], "shape"),
        (np.zeros((3, 3)), [[0, 1]], "shape"),
        (np.zeros((3, 3)), [[0.0, 1.0, 2.0]], "integers"),
        (np.array([["a", "b", "c"]] * 3), [[0, 1, 2]], "numbers"),
    ],
)
def test_bad_meshes_raise_value_error(vertices, faces, message):
    with pytest.raises(ValueError, match=message):
        meshbool.Mesh(vertices, faces)
    with pytest.raises(ValueError, match=message):
        meshbool.boolean((vertices, faces), meshbool.box([0, 0, 0], [1, 1, 1]), "union")


def test_non_finite_coordinates_are_refused_by_operations():
    v = meshbool.box([0, 0, 0], [1, 1, 1]).vertices.copy()
    v[3, 1] = np.nan
    bad = meshbool.Mesh(v, meshbool.box([0, 0, 0], [1, 1, 1]).faces)
    for call in [
        lambda: meshbool.boolean(bad, meshbool.box([2, 2, 2], [3, 3, 3]), "union"),
        lambda: meshbool.split(bad, bad),
        lambda: meshbool.curves(bad, bad),
        lambda: meshbool.orient(bad),
        lambda: meshbool.repair(bad),
        lambda: meshbool.close(bad),
        lambda: meshbool.pick([bad]),
    ]:
        with pytest.raises(ValueError, match="non-finite"):
            call()
    with pytest.raises(ValueError, match="unknown operation"):
        meshbool.boolean(bad, bad, "xor")
    with pytest.raises(ValueError, match="expected a mesh"):
        meshbool.boolean(42, bad, "union")


def test_volume_identities_on_spheres():
    a = uv_sphere([0, 0, 0], 1.0, 32, 16)
    b = uv_sphere([0.6, 0.1, 0.05], 0.8, 28, 14)
    va, vb = meshbool.Mesh(*a).volume, meshbool.Mesh(*b).volume
    r = {op: meshbool.boolean(a, b, op) for op in meshbool.OPERATIONS}
    for op, m in r.items():
        assert m.is_closed, op
        assert m.report["boundary_edges"] == 0 and m.report["non_manifold_edges"] == 0
        assert m.report["volume"] == m.volume
        assert len(m.provenance["source"]) == len(m.faces)
    u, i = r["union"].volume, r["intersection"].volume
    assert abs(u + i - va - vb) < 1e-9 * va
    assert abs(r["difference"].volume - (va - i)) < 1e-9 * va
    assert abs(r["reverse_difference"].volume - (vb - i)) < 1e-9 * va
    # Aliases, and provenance: the subtracted part is flipped and comes from b.
    d = meshbool.boolean(a, b, "subtract")
    np.testing.assert_array_equal(d.faces, r["difference"].faces)
    p = d.provenance
    assert set(np.unique(p["source"])) == {0, 1}
    np.testing.assert_array_equal(p["flipped"], p["source"] == 1)
    assert p["triangle"][p["source"] == 0].max() < len(a[1])
    # Made on first use, then kept; a mesh's provenance can be replaced.
    assert d.provenance is p and p["source"].dtype == np.uint8
    assert p["triangle"].dtype == np.uint32 and p["flipped"].dtype == np.bool_
    d.provenance = {"triangle": p["triangle"]}
    assert list(d.provenance) == ["triangle"]


@needs_shared_data
def test_kirra_terrain_minus_cylinder_split_and_pick(tmp_path):
    terrain = meshbool.read(SHARED / "kirra_terrain.obj")
    cylinder = meshbool.read(SHARED / "kirra_cylinder.obj")
    with pytest.raises(ValueError, match="46 inconsistently oriented edges"):
        meshbool.split(terrain, cylinder, orient=False)
    # Oriented at the door by default: the same as orienting it first.
    d = meshbool.boolean(terrain, cylinder, "difference")
    assert d.report["operands"][0]["reoriented_triangles"] == 22
    up = meshbool.orient(terrain, "z-up")
    np.testing.assert_array_equal(d.faces, meshbool.boolean(up, cylinder, "difference").faces)
    assert up.report["flipped"] == 22
    s = meshbool.split(up, cylinder)
    assert s.groups == ["a_in_b", "a_out_b", "b_in_a", "b_out_a"]
    counts = {g: len(s.group(g)) for g in s.groups}
    assert counts == {"a_in_b": 881, "a_out_b": 10629, "b_in_a": 185, "b_out_a": 185}
    assert len(s.a_on_b_same) == 0
    assert [len(c) for c in s.components("a_out_b")] == [10629]
    mined = s.pick("a_out_b", "b_in_a:flip")
    # The split's clean-up removes the 16 seam points where the rim is straight (one
    # triangle in each of the four groups), as the boolean's does (2 triangles each of
    # its result); with every seam point kept, the raw groups and the raw boolean.
    assert s.report("obj")["cleanup"]["removed_points"] == 16
    kept = meshbool.split(up, cylinder, keep_seam_points=True)
    assert {g: len(kept.group(g)) for g in kept.groups} == {
        "a_in_b": 897, "a_out_b": 10645, "b_in_a": 201, "b_out_a": 201
    }
    diff = meshbool.boolean(up, cylinder, "difference")
    raw = meshbool.boolean(up, cylinder, "difference", keep_seam_points=True)
    assert len(mined) == len(diff) == len(raw) - 32 and mined.report["boundary_edges"] == 560
    assert len(kept.pick("a_out_b", "b_in_a:flip")) == len(raw)
    assert diff.report["cleanup"]["removed_points"] == 16
    assert abs(mined.volume - diff.volume) < 1e-6 * abs(diff.volume)
    with pytest.raises(ValueError, match="a piece may be picked once"):
        s.pick("a_out_b", "a_out_b#0")
    manifest = s.write(tmp_path / "pieces", "obj")
    assert manifest == s.report("obj")
    assert json.loads((tmp_path / "pieces" / "manifest.json").read_text()) == manifest
    assert (tmp_path / "pieces" / "a_out_b.obj").exists()


def test_trimesh_round_trip():
    trimesh = pytest.importorskip("trimesh")
    a = trimesh.creation.icosphere(subdivisions=3)
    b = a.copy()
    b.apply_translation([0.4, 0.2, 0.1])
    u = meshbool.boolean(a, b, "union")
    t = u.to_trimesh()
    assert t.is_watertight and t.is_winding_consistent
    assert abs(t.volume - u.volume) < 1e-9 * u.volume
    i = meshbool.boolean(t, b, "intersection")
    assert abs(i.volume - b.volume) < 1e-9 * b.volume


def test_curves_are_closed_loops():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    b = meshbool.box([0.5, 0.5, -1], [1.5, 1.5, 2])
    # B pierces a corner of A top to bottom: one loop over A's top, down A's side, along
    # its bottom and up again, of length 0.5 + 0.5 + 1 + 0.5 + 0.5 + 1.
    c = meshbool.curves(a, b)
    assert [p.closed for p in c] == [True]
    assert c.report["loops"] == 1 and c.report["open_chains"] == 0
    assert all(p.points.shape[1] == 3 for p in c)
    length = sum(
        np.linalg.norm(np.roll(p.points, -1, axis=0) - p.points, axis=1).sum() for p in c
    )
    assert abs(length - c.report["total_length"]) < 1e-12
    assert abs(length - 4.0) < 1e-12
    # Tagged raw segments lie in the triangles they name; simplify thins the loop.
    t = meshbool.curves(a, b, tagged=True).report["tagged_segments"]
    assert len(t) >= c.report["segments"]
    av = np.asarray(a.vertices)[np.asarray(a.faces)]
    for s in t:
        lo, hi = av[s["tri_a"]].min(axis=0), av[s["tri_a"]].max(axis=0)
        assert np.all(np.asarray(s["p0"]) >= lo) and np.all(np.asarray(s["p0"]) <= hi)
    thin = meshbool.curves(a, b, simplify=0.75)
    assert thin.report["simplified_points_removed"] > 0
    assert len(thin[0].points) < len(c[0].points)


def test_classify_points_inside_outside_on():
    cube = meshbool.box([0, 0, 0], [1, 1, 1])
    pts = np.array([[0.5, 0.5, 0.5], [2, 0, 0], [1, 0.5, 0.25], [0, 0, 0]])
    classes, winding = meshbool.classify(cube, pts)
    assert [meshbool.POINT_CLASSES[c] for c in classes] == ["inside", "outside", "on", "on"]
    assert abs(winding[0] - 1) < 1e-9 and abs(winding[1]) < 1e-9
    with pytest.raises(ValueError, match="non-finite"):
        meshbool.classify(cube, [[np.nan, 0, 0]])


def test_orient_close_repair():
    box = meshbool.box([0, 0, 0], [1, 1, 1])
    inside_out = meshbool.Mesh(box.vertices, box.faces[:, ::-1])
    assert inside_out.volume == -1.0
    assert meshbool.orient(inside_out, "outward").volume == 1.0
    open_box = meshbool.Mesh(box.vertices, box.faces[:10])
    assert not open_box.is_closed
    capped = meshbool.close(open_box, "cap")
    assert capped.is_closed and capped.volume == 1.0
    assert capped.report["cap"]["capped"] == 1
    fixed = meshbool.repair(open_box, close="cap", orient="outward")
    assert fixed.is_closed and fixed.volume == 1.0
    assert fixed.report["before"]["boundary_edges"] == 4
    with pytest.raises(ValueError, match="not a repair configuration"):
        meshbool.repair(open_box, wled=0.1)
    with pytest.raises(ValueError, match="floor offset"):
        meshbool.close(open_box, "curtain", floor_offset=-1.0)


def test_touching_cubes_union_is_manifold():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    b = meshbool.box([1, 1, 0], [2, 2, 1])
    u = meshbool.boolean(a, b, "union", threads=1)
    assert u.is_closed and u.volume == 2.0
    assert u.report["split_nonmanifold"]["edges_split"] == 1
    kept = meshbool.boolean(a, b, "union", keep_nonmanifold=True)
    assert kept.stats()["non_manifold_edges"] == 1
    assert meshbool.pick([a, b]).stats()["non_manifold_edges"] == 0


def test_forced_inputs_list_what_was_assumed():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    two = meshbool.Mesh(
        np.vstack([a.vertices, a.vertices + 0.5]), np.vstack([a.faces, a.faces + 8])
    )
    far = meshbool.box([3, 3, 3], [4, 4, 4])
    with pytest.raises(ValueError, match="self-intersecting triangle pairs"):
        meshbool.boolean(two, far, "union", resolve=False)
    r = meshbool.boolean(two, far, "union", force=True, resolve=False)
    assert len(r.assumed) == 1 and "taken as given" in r.assumed[0]
    unchecked = meshbool.boolean(a, a, "union", self_check=False)
    assert unchecked.volume == 1.0
    assert unchecked.assumed == [
        "A: not checked for self-intersections",
        "B: not checked for self-intersections",
    ]


def test_operands_are_checked_once_for_many_booleans():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    two = meshbool.Mesh(
        np.vstack([a.vertices, a.vertices + 0.5]), np.vstack([a.faces, a.faces + 8])
    )
    b = meshbool.Mesh(*uv_sphere([1.1, 1.2, 0.9], 0.6, 32, 16))
    # Resolved on the way in, once: its mesh is the solid the two cubes enclose.
    prepared = meshbool.Operand(two, name="two cubes")
    assert prepared.report["resolved"]["components"] == 2
    assert prepared.report["name"] == "two cubes"
    assert prepared.mesh.is_closed and prepared.mesh.volume == 2.0 - 0.125
    for op in ("union", "intersection", "difference", "reverse_difference"):
        plain = meshbool.boolean(two, b, op)
        both = meshbool.boolean(prepared, meshbool.Operand(b), op)
        mixed = meshbool.boolean(prepared, b, op)
        for r in (both, mixed):
            assert np.array_equal(r.vertices, plain.vertices), op
            assert np.array_equal(r.faces, plain.faces), op
            for key in ("source", "triangle", "flipped"):
                assert np.array_equal(r.provenance[key], plain.provenance[key]), op
            assert r.is_closed and r.volume == plain.volume
    assert mixed.report["operands"][0]["name"] == "two cubes"
    # Refused as a boolean would refuse it, unless forced.
    with pytest.raises(ValueError, match="self-intersecting triangle pairs"):
        meshbool.Operand(two, resolve=False)
    forced = meshbool.Operand(two, resolve=False, force=True)
    assert forced.report["forced"]
    with pytest.raises(ValueError, match="expected a mesh"):
        meshbool.Operand("no mesh")


def test_overlapping_parts_are_resolved():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    two = meshbool.Mesh(
        np.vstack([a.vertices, a.vertices + 0.5]), np.vstack([a.faces, a.faces + 8])
    )
    r = meshbool.resolve(two)
    assert r.is_closed and r.volume == 2.0 - 0.125
    assert r.report["resolve"]["united_components"] == 2
    assert r.provenance["triangle"].shape == (len(r),)
    assert set(np.unique(r.provenance["triangle"] // 12)) == {0, 1}
    # As an operand: resolved on the way in, the identity holds with the resolved volume.
    b = meshbool.Mesh(*uv_sphere([1.1, 1.2, 0.9], 0.6, 32, 16))
    u = meshbool.boolean(two, b, "union")
    i = meshbool.boolean(two, b, "intersection")
    assert u.report["operands"][0]["resolved"]["components"] == 2
    assert u.is_closed and i.is_closed
    assert abs(u.volume + i.volume - r.volume - b.volume) < 1e-12
    # A cube with a corner pushed through its bottom crosses itself: cut along its own
    # seam. Winding 1, 0 or -1: vol(nonzero) + signed volume = 2 vol(positive).
    v = a.vertices.copy()
    v[np.all(v == 1.0, axis=1)] = [0.5, 0.5, -0.5]
    folded = meshbool.Mesh(v, a.faces)
    pos, nonzero = meshbool.resolve(folded), meshbool.resolve(folded, "nonzero")
    assert pos.is_closed and nonzero.is_closed
    assert abs(nonzero.volume + folded.volume - 2 * pos.volume) < 1e-12
    assert pos.report["resolve"]["patches"] >= 3
    # Open and crossing itself: cannot be resolved.
    with pytest.raises(ValueError, match="not closed"):
        meshbool.resolve(meshbool.Mesh(v, a.faces[1:]))
    with pytest.raises(ValueError, match="fill rule"):
        meshbool.resolve(two, "odd")


def test_self_curves():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    two = meshbool.Mesh(
        np.vstack([a.vertices, a.vertices + 0.5]), np.vstack([a.faces, a.faces + 8])
    )
    own = meshbool.curves(two)
    assert len(own) == 1 and own[0].closed
    assert abs(own.report["total_length"] - 3.0) < 1e-12
    assert meshbool.curves(a).report["points"] == 0


def fanned_prism(n, turn):
    """A prism of height 1 on a regular ``n``-gon of circumradius 1 turned by ``turn``
    radians, both caps fanned from its first vertex (a CAD exporter's caps)."""
    ring = [[math.cos(turn + 2 * math.pi * i / n), math.sin(turn + 2 * math.pi * i / n)]
            for i in range(n)]
    v = [[x, y, 0.0] for x, y in ring] + [[x, y, 1.0] for x, y in ring]
    f = [[0, i + 1, i] for i in range(1, n - 1)] + [[n, n + i, n + i + 1] for i in range(1, n - 1)]
    for i in range(n):
        j = (i + 1) % n
        f += [[i, j, n + j], [i, n + j, n + i]]
    return np.array(v), np.array(f, dtype=np.uint32)


def test_coplanar_refinement_cuts_shared_faces_along_both_triangulations():
    # Two fanned 24-sided prisms on one base, the second turned by half a side: their
    # caps overlap in a regular 48-gon of inradius cos(pi / 24) where every fan triangle
    # of one crosses many of the other's.
    n = 24
    a, b = fanned_prism(n, 0.0), fanned_prism(n, math.pi / n)
    r = math.cos(math.pi / n)
    want = 2 * n * r * r * math.tan(math.pi / (2 * n))
    lean = meshbool.boolean(a, b, "intersection", keep_seam_points=True)
    refined = meshbool.boolean(a, b, "intersection", keep_seam_points=True,
                               coplanar_refinement=True)
    for m in (lean, refined):
        assert m.is_closed and m.report["non_manifold_edges"] == 0
        assert abs(m.volume - want) < 1e-12
    assert len(refined) > 2 * len(lean), (len(refined), len(lean))
    # The default clean-up takes the cut points back out of the flat caps.
    assert len(meshbool.boolean(a, b, "intersection", coplanar_refinement=True)) < len(refined)
    # Splits: the shared caps' groups hold the refinement too, and picking the same pieces
    # from either split gives the same solid.
    s_lean = meshbool.split(a, b, keep_seam_points=True)
    s_refined = meshbool.split(a, b, keep_seam_points=True, coplanar_refinement=True)
    assert len(s_refined.a_on_b_same) > 2 * len(s_lean.a_on_b_same) > 0
    for s in (s_lean, s_refined):
        got = s.pick(op="intersection")
        assert got.is_closed and abs(got.volume - want) < 1e-12
    # Curves: the refinement adds the segments where either fan's edges cross the other's
    # cap.
    c_lean = meshbool.curves(a, b, tagged=True).report
    c_refined = meshbool.curves(a, b, tagged=True, coplanar_refinement=True).report
    assert len(c_refined["tagged_segments"]) > 2 * len(c_lean["tagged_segments"])


def test_split_pick_by_op_is_the_boolean():
    a = meshbool.box([0, 0, 0], [1, 1, 1])
    b = meshbool.box([0.5, 0.5, 0.5], [1.5, 1.5, 1.5])
    s = meshbool.split(a, b)
    for op, volume in [("union", 1.875), ("intersection", 0.125), ("difference", 0.875)]:
        r = s.pick(op=op)
        assert r.is_closed and r.volume == volume
        assert r.volume == meshbool.boolean(a, b, op).volume
    with pytest.raises(ValueError, match="not both"):
        s.pick("a_out_b", op="union")


def test_union_of_many_in_one_call():
    cubes = [
        meshbool.box([0, 0, 0], [2, 2, 2]),
        meshbool.box([1, 1, 1], [3, 3, 3]),
        meshbool.box([1.5, 1.5, -1], [2.5, 2.5, 4]),
    ]
    u = meshbool.boolean_many(cubes, "union")
    assert u.is_closed and u.volume == 17.75
    assert set(np.unique(u.provenance["input"])) == {0, 1, 2}
    assert len(u.report["operands"]) == 3
    i = meshbool.boolean_many(cubes, "intersection", threads=1)
    assert i.volume == 0.25
    assert u.report["combined"] == "pairwise_tree"
    # In one arrangement of all three: the same exact solids.
    for op, volume in [("union", 17.75), ("intersection", 0.25)]:
        one = meshbool.boolean_many(cubes, op, one_arrangement=True)
        assert one.is_closed and one.volume == volume
        assert one.report["combined"] == "one_arrangement"
    # B − A of many has no meaning: refused (a difference of many is the first less the
    # others, test_boolean_many_difference_is_the_first_less_the_others).
    with pytest.raises(ValueError, match="only union and intersection"):
        meshbool.boolean_many(cubes, "reverse_difference")


def test_files_round_trip_and_os_errors(tmp_path):
    s = meshbool.Mesh(*uv_sphere([478000.0, 6771000.0, 300.0], 5.0, 16, 8))
    for name in ["s.obj", "s.ply", "s.dxf", "s.json"]:
        meshbool.write(tmp_path / name, s)
        back = meshbool.read(tmp_path / name)
        assert back.volume == s.volume and len(back) == len(s), name
    meshbool.write(tmp_path / "s.txt", s, format="ply-ascii")
    assert meshbool.read(tmp_path / "s.txt", format="ply").volume == s.volume
    with pytest.raises(OSError):
        meshbool.read(tmp_path / "missing.obj")
    with pytest.raises(OSError):
        meshbool.write(tmp_path / "no" / "such" / "dir.obj", s)
    (tmp_path / "bad.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
    with pytest.raises(ValueError, match="line 3"):
        meshbool.read(tmp_path / "bad.obj")
    with pytest.raises(ValueError, match="threads"):
        meshbool.boolean(s, s, "union", threads=100_000)


def test_work_runs_without_the_gil():
    # While a boolean runs in a worker thread, the main thread keeps running Python:
    # with the GIL held through the call it would stall until the call returned.
    import threading
    import time

    a = uv_sphere([0, 0, 0], 1.0, 160, 80)
    b = uv_sphere([0.5, 0, 0], 1.0, 160, 80)
    inside = threading.Event()
    results = []

    def work():
        inside.set()
        for _ in range(3):
            results.append(meshbool.boolean(a, b, "union").volume)

    worker = threading.Thread(target=work)
    worker.start()
    inside.wait()
    ticks, start = 0, time.perf_counter()
    while worker.is_alive():
        ticks += 1
    elapsed = time.perf_counter() - start
    assert len(results) == 3 and results[0] == results[2]
    # Python ran throughout: at least one tick per 10 microseconds of the worker's time.
    assert elapsed > 0.05 and ticks > elapsed * 1e5, (ticks, elapsed)


def test_terrain_and_pit_generators():
    t, p = meshbool.terrain(), meshbool.pit()
    # The documented defaults: the figures of `meshbool make terrain|pit --json`.
    assert (len(t.faces), len(t.vertices), t.report["boundary_edges"]) == (20000, 10201, 400)
    assert (len(p.faces), len(p.vertices), p.report["boundary_edges"]) == (1216, 641, 64)
    assert t.report["shape"] == "terrain" and p.report["shape"] == "pit"
    assert t.vertices.min(axis=0).tolist() == [-500.0, -500.0, -20.0]
    assert t.vertices.max(axis=0).tolist() == [500.0, 500.0, 20.0]
    assert p.vertices.min(axis=0).tolist() == [-220.0, -160.0, -80.0]
    assert p.vertices.max(axis=0).tolist() == [220.0, 160.0, 60.0]
    for m in (t, p):
        assert not m.is_closed and m.report["non_manifold_edges"] == 0
        # Facing up: every triangle's normal has a positive z.
        q = m.vertices[m.faces]
        nz = (q[:, 1, 0] - q[:, 0, 0]) * (q[:, 2, 1] - q[:, 0, 1]) - (
            q[:, 2, 0] - q[:, 0, 0]
        ) * (q[:, 1, 1] - q[:, 0, 1])
        assert nz.min() > 0
    # A function of its seed; one number for both sizes and counts; at UTM coordinates.
    again = meshbool.terrain(seed=1)
    assert again.vertices.tobytes() == t.vertices.tobytes()
    assert (meshbool.terrain(seed=2).vertices != t.vertices).any()
    utm = meshbool.terrain((478600, 6772300, 400), size=300, cells=(30, 20), relief=12.5)
    assert len(utm.faces) == 1200 and utm.report["boundary_edges"] == 100
    assert utm.vertices.min(axis=0).tolist() == [478450.0, 6772150.0, 393.75]
    circle = meshbool.pit((1, 2, -3), radius=50, depth=30, benches=3, berm=0, segments=12)
    assert (len(circle.faces), len(circle.vertices)) == (84, 49)
    # They cross along one closed curve. Split there, the terrain outside the rim and the
    # shell below the ground are the ground after digging, the terrain's outline its only
    # boundary; the cut is the material above the shell.
    s = meshbool.split(t, p)
    assert s.groups == ["a_in_b", "a_out_b", "b_in_a", "b_out_a"]
    after = s.pick("a_in_b", "b_in_a")
    assert after.report["boundary_edges"] == 400 and after.report["non_manifold_edges"] == 0
    assert len(after) == len(s.a_in_b) + len(s.b_in_a)
    assert abs(after.area - s.a_in_b.area - s.b_in_a.area) < 1e-9 * after.area
    report, lines = meshbool.cutfill(p, t)
    assert report["zero_lines"] == 1 and len(lines) == 1 and lines[0].closed
    assert report["cut"] > 1e6 and report["fill"] > 1e5
    assert abs(report["common_plan_area"] - report["design_plan_area"]) < 1e-6
    for bad in [
        lambda: meshbool.terrain(size=0),
        lambda: meshbool.terrain(size=(1, 2, 3)),
        lambda: meshbool.terrain(cells=0),
        lambda: meshbool.terrain(cells=(4, -1)),
        lambda: meshbool.terrain(relief=-1),
        lambda: meshbool.terrain(seed=-1),
        lambda: meshbool.terrain(seed=2**64),
        lambda: meshbool.terrain(center=(0, 0)),
        lambda: meshbool.pit(radius=100),
        lambda: meshbool.pit(benches=0),
        lambda: meshbool.pit(segments=2.5),
        lambda: meshbool.pit(berm=float("nan")),
    ]:
        with pytest.raises(ValueError):
            bad()
    with pytest.raises(ValueError, match="reach 102 in from the rim"):
        meshbool.pit(radius=100)


def test_cutfill_of_a_slope_against_flat_ground():
    # Ground z = 0 and a slope z = x - 2 over [0, 4] x [0, 1]: the wedges above and below
    # are 1 * 2 * 2 / 2 = 2 each, meeting along x = 2.
    xs, ys = np.meshgrid([0.0, 2.0, 4.0], [0.0, 1.0], indexing="ij")
    pts = np.c_[xs.ravel(), ys.ravel()]
    faces = np.array([[0, 2, 3], [0, 3, 1], [2, 4, 5], [2, 5, 3]], dtype=np.uint32)
    ground = (np.c_[pts, np.zeros(len(pts))], faces)
    slope = (np.c_[pts, pts[:, 0] - 2.0], faces)
    report, lines = meshbool.cutfill(ground, slope)
    assert abs(report["cut"] - 2.0) < 1e-12 and abs(report["fill"] - 2.0) < 1e-12
    assert abs(report["common_plan_area"] - 4.0) < 1e-12
    assert len(lines) == 1 and report["zero_lines"] == 1


def shortest_edge_and_altitude(m):
    """The shortest edge and the smallest altitude of a mesh's triangles."""
    p = m.vertices[m.faces]
    edges = np.linalg.norm(np.roll(p, -1, axis=1) - p, axis=2)
    twice_area = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    return edges.min(), (twice_area / edges.max(axis=1)).min()


def test_snap_removes_needles_of_a_cutter_drawn_a_little_larger():
    # The unit cube minus a box over its corner x > 0.5, z > 0.5 whose other walls lie 1e-3
    # outside the cube: the exact result has edges and altitudes of about 1e-3.
    cube = meshbool.box([0, 0, 0], [1, 1, 1])
    cutter = meshbool.box([0.5, -0.001, 0.5], [1.001, 1.001, 1.001])
    # (On the arrangement as it is: by default the exact clean-up already removes the
    # straight seam points that make these needles, see below.)
    exact = meshbool.boolean(cube, cutter, "difference", keep_seam_points=True)
    assert "snap" not in exact.report
    assert exact.report["cleanup"]["removed_points"] == 0
    assert min(shortest_edge_and_altitude(exact)) < 1e-3
    d = 0.01
    snapped = meshbool.boolean(cube, cutter, "difference", snap=d, keep_seam_points=True)
    assert snapped.is_closed and snapped.stats()["non_manifold_edges"] == 0
    assert min(shortest_edge_and_altitude(snapped)) >= d
    assert abs(snapped.volume - exact.volume) <= d * exact.area
    s = snapped.report["snap"]
    assert s["tolerance"] == d and s["left"] == 0 and s["collapsed"] > 0
    assert s["max_move"] <= d
    assert len(snapped.provenance["source"]) == len(snapped.faces)
    # The same through resolve and repair; a negative tolerance is refused.
    for m in (meshbool.resolve(exact, snap=d), meshbool.repair(exact, snap=d)):
        assert m.is_closed and min(shortest_edge_and_altitude(m)) >= d
        assert m.report["snap"]["collapsed"] > 0
    with pytest.raises(ValueError, match="snap"):
        meshbool.boolean(cube, cutter, "union", snap=-1.0)
    # The default result: the same solid, cleaned exactly (no vertex moved) to the fewest
    # triangles an L-shaped prism has, without needles.
    clean = meshbool.boolean(cube, cutter, "difference")
    assert len(clean.faces) == 20 and clean.volume == 0.75 and clean.is_closed
    assert clean.report["cleanup"]["removed_points"] == 6
    assert min(shortest_edge_and_altitude(clean)) >= d
    many = meshbool.boolean_many([cube, cutter], "union", keep_seam_points=True)
    assert many.report["cleanup"]["removed_points"] == 0


def test_split_and_pick_snap():
    # The same pair split with snap: the groups snapped together stay one piece each,
    # without edges under the tolerance, and every boolean picked from them is closed.
    cube = meshbool.box([0, 0, 0], [1, 1, 1])
    cutter = meshbool.box([0.5, -0.001, 0.5], [1.001, 1.001, 1.001])
    d = 0.01
    s = meshbool.split(cube, cutter, snap=d)
    rep = s.report()
    assert rep["snap"]["left"] == 0 and rep["snap"]["collapsed"] > 0
    assert "snap" not in meshbool.split(cube, cutter).report()
    for name in ("a_in_b", "a_out_b", "b_in_a", "b_out_a"):
        assert len(s.components(name)) == 1
        assert min(shortest_edge_and_altitude(s.group(name))) >= d
    for op, volume in (("union", 1.0), ("intersection", 0.25), ("difference", 0.75)):
        m = s.pick(op=op)
        assert m.is_closed and m.stats()["non_manifold_edges"] == 0
        assert abs(m.volume - volume) <= d * m.area
    # pick with snap, from the exact split with every seam point: the snapped difference.
    exact = meshbool.split(cube, cutter, keep_seam_points=True)
    m = exact.pick(op="difference", snap=d)
    assert m.is_closed and m.report["snap"]["left"] == 0
    assert len(m.faces) == 24 and m.volume == 0.75
    # The split's exact clean-up (the default) already gives the coarsest difference.
    clean = meshbool.split(cube, cutter)
    assert clean.report()["cleanup"]["removed_points"] == 6
    m = clean.pick(op="difference")
    assert m.is_closed and len(m.faces) == 20 and m.volume == 0.75
    parts = [(exact.a_out_b, False), (exact.b_in_a, True)]
    assert meshbool.pick(parts, snap=d).report["snap"]["collapsed"] > 0
    with pytest.raises(ValueError, match="snap"):
        meshbool.split(cube, cutter, snap=-1.0)


@needs_shared_data
def test_envelopes_of_the_folded_kirra_terrain():
    terrain = meshbool.read(SHARED / "kirra_terrain.obj")
    for side in ["upper", "lower"]:
        env = meshbool.envelope(terrain, side)
        r = env.report["envelope"]
        assert r["side"] == side
        assert r["folded_triangles"] == 22 and r["hidden_triangles"] == 22
        assert env.report["boundary_edges"] == 560
        assert env.provenance["triangle"].shape == (len(env),)
        assert env.provenance["triangle"].max() < len(terrain)
        # Faced up everywhere but its vertical walls, over the terrain's plan area.
        p = env.vertices[env.faces]
        plan = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (
            p[:, 2, 0] - p[:, 0, 0]
        ) * (p[:, 1, 1] - p[:, 0, 1])
        assert plan.min() > -1e-9
    with pytest.raises(ValueError, match="closed"):
        meshbool.envelope(meshbool.box([0, 0, 0], [1, 1, 1]))


def grid_sphere(center, n):
    """A closed UV sphere of radius 1 with 2n meridians and n bands (4n(n - 1)
    triangles), built with numpy."""
    i, j = np.meshgrid(np.arange(1, n), np.arange(2 * n), indexing="ij")
    theta, phi = np.pi * i / n, np.pi * j / n
    ring = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1)
    verts = np.vstack([[[0, 0, 1], [0, 0, -1]], ring.reshape(-1, 3)]) + np.asarray(center, float)
    at = lambda i, j: 2 + (i - 1) * 2 * n + j % (2 * n)  # noqa: E731
    j = np.arange(2 * n)
    faces = [np.stack([np.zeros_like(j), at(1, j), at(1, j + 1)], -1)]
    faces.append(np.stack([np.ones_like(j), at(n - 1, j + 1), at(n - 1, j)], -1))
    ii, jj = np.meshgrid(np.arange(1, n - 1), j, indexing="ij")
    a, b, c, d = at(ii, jj), at(ii, jj + 1), at(ii + 1, jj), at(ii + 1, jj + 1)
    faces.append(np.stack([a, c, b], -1).reshape(-1, 3))
    faces.append(np.stack([b, c, d], -1).reshape(-1, 3))
    return verts, np.vstack(faces).astype(np.uint32)


def test_ctrl_c_stops_a_long_boolean_with_keyboard_interrupt():
    """KeyboardInterrupt (Ctrl-C; here raised by interrupt_main from a timer) stops a
    long boolean at the library's next stage instead of at its end; the next call works."""
    import _thread
    import threading
    import time

    a, b = grid_sphere([0, 0, 0], 400), grid_sphere([0.5, 0, 0], 400)
    t0 = time.perf_counter()
    assert meshbool.boolean(a, b, "union").is_closed
    full = time.perf_counter() - t0
    timer = threading.Timer(0.2 * full, _thread.interrupt_main)
    t0 = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        meshbool.boolean(a, b, "union")
    stopped = time.perf_counter() - t0
    timer.join()
    assert stopped < 0.8 * full, (stopped, full)
    again = meshbool.boolean(grid_sphere([0, 0, 0], 12), grid_sphere([0.5, 0, 0], 12), "union")
    assert again.is_closed


def test_csg_scene_with_meshes_in_memory_a_cache_and_failures(tmp_path):
    """A CSG document as a dict (a mesh in memory beside primitives, a cutter), then from a
    file: the volume of the booleans it names; with one cache, a second call computes
    nothing and an edit only its path; a node that fails is named."""
    block = meshbool.box([0, 0, 0], [4, 2, 2])

    def scene(slot_width):
        return {
            "root": {
                "op": "difference",
                "name": "slotted",
                "children": [
                    {"op": "union", "children": [
                        {"mesh": block},
                        {"primitive": "cube", "min": [4, 0, 0], "max": [6, 2, 2]},
                    ]},
                    {"primitive": "cube", "min": [1, -1, -1], "max": [1 + slot_width, 3, 3],
                     "role": "cutter"},
                ],
            }
        }

    cache = meshbool.CsgCache()
    out = meshbool.csg(scene(1), cache=cache)
    assert out.is_closed and out.volume == 24 - 4
    report = out.report
    assert report["computed"] == 5 and report["cached"] == 0
    assert [n["path"] for n in report["nodes"]][-1] == "root"
    assert report["nodes"][-1]["name"] == "slotted"
    again = meshbool.csg(scene(1), cache=cache)
    assert again.report["computed"] == 0 and len(again.report["nodes"]) == 1
    assert np.array_equal(again.vertices, out.vertices)
    edited = meshbool.csg(scene(2), cache=cache)
    assert edited.volume == 24 - 8
    assert [n["path"] for n in edited.report["nodes"] if n["source"] == "computed"] == [
        "root.children[1]", "root"]

    # From a file, paths relative to it, with a folder cache shared by two caches.
    meshbool.write(str(tmp_path / "block.ply"), block)
    doc = scene(1)
    doc["root"]["children"][0]["children"][0] = {"mesh": "block.ply"}
    (tmp_path / "scene.json").write_text(json.dumps(doc))
    first = meshbool.csg(tmp_path / "scene.json", cache=meshbool.CsgCache(tmp_path / "cache"))
    second = meshbool.csg(str(tmp_path / "scene.json"), cache=meshbool.CsgCache(tmp_path / "cache"))
    assert first.volume == 20 and second.report["nodes"][0]["source"] == "disk"
    assert np.array_equal(first.vertices, second.vertices)

    # A node that fails, and a malformed document.
    doc["root"]["children"][0]["children"][0] = {"mesh": "nowhere.stl"}
    with pytest.raises(ValueError, match=r"node root\.children\[0\]\.children\[0\] failed") as e:
        meshbool.csg(doc, base=tmp_path)
    assert e.value.report["failed"]["path"] == "root.children[0].children[0]"
    with pytest.raises(ValueError, match=r"root\.children\[0\]\.radus: unknown key"):
        meshbool.csg({"root": {"op": "union", "children": [{"primitive": "sphere", "radus": 1}]}})


def test_boolean_many_difference_is_the_first_less_the_others():
    """``boolean_many(meshes, "difference")``: the first mesh less all the others (here
    two slots through a bar, one of them overlapping a third cutter), exact volumes; the
    provenance names inputs by position."""
    bar = meshbool.box([0, 0, 0], [4, 1, 1])
    slots = [meshbool.box([0.5, -1, -1], [1, 2, 2]), meshbool.box([2.5, -1, -1], [3, 2, 2]),
             meshbool.box([2.75, -1, -1], [3.25, 2, 2])]
    out = meshbool.boolean_many([bar, *slots], "difference")
    assert out.is_closed and out.volume == 4 - 0.5 - 0.75
    assert set(np.unique(out.provenance["input"])) == {0, 1, 2, 3}
    assert len(out.report["operands"]) == 4


def test_terrain_and_pit_show_the_librarys_defaults():
    # The signatures' literals are the library's own defaults (Shape::TERRAIN, Shape::PIT),
    # parameter for parameter, and the call without arguments makes the library's shape.
    from meshbool import _native

    defaults = json.loads(_native.shape_defaults())
    for fn in (meshbool.terrain, meshbool.pit):
        lib = defaults[fn.__name__]
        params = inspect.signature(fn).parameters
        assert set(params) == set(lib), fn.__name__
        for name, value in lib.items():
            shown = params[name].default
            shown = list(shown) if isinstance(shown, tuple) else shown
            assert shown == value, (fn.__name__, name, shown, value)
