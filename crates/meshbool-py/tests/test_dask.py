"""meshbool.dask on a local cluster of two worker processes: the results equal the one-machine
calls, in input order, failures in their place."""

import pathlib
import pickle

import numpy as np
import pytest

import meshbool

distributed = pytest.importorskip("distributed", reason="meshbool[dask] is not installed")
import meshbool.dask as mbd  # noqa: E402

SHARED = pathlib.Path(__file__).resolve().parents[4] / "shared" / "data"


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def close(a, b, rel=1e-9):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def test_a_result_pickles_with_its_report_and_provenance():
    u = meshbool.boolean(meshbool.box([0, 0, 0], [1, 1, 1]), meshbool.box([0.5] * 3, [2] * 3), "union")
    back = pickle.loads(pickle.dumps(u))
    assert np.array_equal(back.vertices, u.vertices) and np.array_equal(back.faces, u.faces)
    assert back.report == u.report and back.volume == u.volume == 1.0 + 1.5**3 - 0.125
    assert np.array_equal(back.provenance["source"], u.provenance["source"])


def test_map_boolean_gives_each_pairs_result_in_order(client, tmp_path):
    boxes = [meshbool.box([0, 0, 0], [1 + k, 1, 1]) for k in range(4)]
    cutter = meshbool.box([0.5, -1, -1], [10, 2, 2])
    # Files read on the workers, meshes sent; one missing file fails in its place.
    paths = []
    for k, b in enumerate(boxes):
        p = tmp_path / f"box{k}.ply"
        meshbool.write(str(p), b)
        paths.append(str(p))
    pairs = [(paths[0], cutter), (boxes[1], cutter), (str(tmp_path / "missing.ply"), cutter), (paths[3], paths[1])]
    got = mbd.map_boolean(pairs, "difference", client)
    assert len(got) == 4
    assert close(got[0].volume, 0.5) and close(got[1].volume, 0.5), got
    assert isinstance(got[2], mbd.Failure) and got[2].index == 2
    assert "missing.ply" in got[2].error
    # box3 [0,4]x... minus box1 [0,2]x...: 2.
    assert close(got[3].volume, 2.0) and got[3].is_closed
    assert got[3].report["operands"][0]["triangles"] == 12
    # The same on one machine, mesh for mesh.
    one = meshbool.boolean(boxes[3], boxes[1], "difference")
    assert np.array_equal(one.vertices, got[3].vertices) and np.array_equal(one.faces, got[3].faces)
    # Written by the workers under a pattern, the paths returned.
    out = str(tmp_path / "out" / "{i}-{a}-{b}.ply")
    written = mbd.map_boolean(pairs[:2] + pairs[3:], "difference", client, out=out)
    assert written[0].endswith("0-box0-b.ply") and written[1].endswith("1-a-b.ply")
    assert written[2].endswith("2-box3-box1.ply")
    assert close(meshbool.read(written[2]).volume, 2.0)
    with pytest.raises(ValueError, match="every result alike"):
        mbd.map_boolean(pairs, "union", client, out=str(tmp_path / "same.ply"))


def test_map_boolean_without_a_client_runs_on_local_threads():
    a, b = meshbool.box([0, 0, 0], [2, 2, 2]), meshbool.box([1, 1, 1], [3, 3, 3])
    got = mbd.map_boolean([(a, b), (b, a)], "intersection")
    assert [g.volume for g in got] == [1.0, 1.0]


def length(line):
    """A polyline's length, a loop's closing segment included."""
    p = np.vstack([line.points, line.points[:1]]) if line.closed else line.points
    return np.linalg.norm(np.diff(p, axis=0), axis=1).sum()


def _whole_and_tiled(design, topo, tiles, client):
    whole, whole_lines = meshbool.cutfill(design, topo)
    for tile in tiles:
        report, lines = mbd.tiled_cutfill(design, topo, tile, client)
        for key in ("cut", "fill", "net", "common_plan_area", "design_plan_area", "topo_plan_area", "zero_line_length"):
            assert close(report[key], whole[key]), (tile, key, report[key], whole[key])
        assert report["faced_up"] == whole["faced_up"]
        assert report["zero_lines"] == whole["zero_lines"] == len(lines), tile
        assert [p.closed for p in lines] == [p.closed for p in whole_lines]
        assert close(sum(length(p) for p in lines), whole["zero_line_length"])
        yield tile, report


def test_tiled_cutfill_equals_the_whole_at_every_tile_size(client):
    terrain, pit = meshbool.terrain(), meshbool.pit()
    tasks = {tile: r["tiles"] for tile, r in _whole_and_tiled(pit, terrain, [40.0, 100.0, 333.0, 5000.0], client)}
    assert tasks[5000.0] == 1 and tasks[40.0] > 50, tasks


@pytest.mark.skipif(not (SHARED / "kirra_terrain.obj").exists(), reason="../shared/data is absent")
def test_tiled_cutfill_of_the_kirra_pit_and_terrain(client):
    terrain = meshbool.read(str(SHARED / "kirra_terrain.obj"))
    pit = meshbool.read(str(SHARED / "kirra_cup.obj"))
    for _ in _whole_and_tiled(pit, terrain, [5.0, 20.0, 50.0, 1000.0], client):
        pass
    # The terrain as the design: its tiles cut the pit's few triangles' neighbourhoods.
    for _ in _whole_and_tiled(terrain, pit, [20.0, 75.0], client):
        pass


def pad(x0, y0, side, n, z):
    """A flat square design pad at height z: (n+1)² vertices, 2n² triangles facing up."""
    xs = np.linspace(x0, x0 + side, n + 1)
    gx, gy = np.meshgrid(xs, np.linspace(y0, y0 + side, n + 1), indexing="ij")
    v = np.stack([gx.ravel(), gy.ravel(), np.full(gx.size, z)], axis=1)
    i = np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]
    a, b, c, d = i.ravel(), (i + n + 1).ravel(), (i + n + 2).ravel(), (i + 1).ravel()
    f = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype(np.uint32)
    return v, f


def test_many_designs_against_one_terrain_in_one_batch(client):
    terrain = meshbool.terrain()
    pits = [
        meshbool.pit(),
        meshbool.pit(center=(150.0, -100.0, 50.0), radius=(120.0, 90.0), depth=60.0),
        pad(-300.0, 200.0, 200.0, 8, 15.0),
    ]
    got = mbd.tiled_cutfill_many(pits, terrain, 75.0, client)
    assert len(got) == 3
    for pit, (report, lines) in zip(pits, got):
        whole, whole_lines = meshbool.cutfill(pit, terrain)
        # Volumes to 1e-9 of the volumes moved (the pad's cut is 0: its tiles' rounding
        # noise adds up to ~1e-10), areas and lengths to 1e-9 of themselves.
        moved = whole["cut"] + whole["fill"]
        for key in ("cut", "fill", "net"):
            assert abs(report[key] - whole[key]) <= 1e-9 * moved, (key, report[key], whole[key])
        for key in ("common_plan_area", "design_plan_area", "topo_plan_area", "zero_line_length"):
            assert close(report[key], whole[key]), (key, report[key], whole[key])
        assert report["zero_lines"] == whole["zero_lines"] == len(lines)
        assert report["faced_up"] == whole["faced_up"] and report["tiles"] >= 1


def test_tiled_cutfill_refuses_what_the_whole_refuses():
    with pytest.raises(ValueError, match="tile must be"):
        mbd.tiled_cutfill(meshbool.pit(), meshbool.terrain(), 0.0)
    empty = (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.uint32))
    with pytest.raises(ValueError, match="no triangles"):
        mbd.tiled_cutfill(empty, meshbool.terrain(), 10.0)
