"""meshbool on Dask: many booleans at once, and cut and fill of large terrains in tiles.

An optional part of the package (``pip install meshbool[dask]``, which brings
``dask[distributed]``). The same code runs on a laptop's ``LocalCluster``, on an HPC
cluster through dask-jobqueue, or on Kubernetes: pass the ``Client`` of the deployment, or
leave ``client`` out to use the current one (``distributed.get_client()``), or, with no
client at all, Dask's local threads.

- :func:`map_boolean`: one task per pair of meshes, results in input order, a failure as
  a :class:`Failure` value in its place (the others go on). Paths are read by the
  workers, so the meshes do not pass through the scheduler.
- :func:`tiled_cutfill`: cut and fill between a design surface and the topography, the
  plan cut into square tiles, one task per tile. Each design triangle belongs to the tile
  holding its centroid (no triangle is cut: no geometry moves); a task gets its tile's
  design triangles and the topography's triangles whose boxes meet theirs, and computes
  the exact cut and fill over the tile's design triangles. The design's triangles are
  shared out without overlap, so the tiles' volumes and areas add up to the whole's,
  whatever the tile size and the number of workers.

>>> import meshbool, meshbool.dask
>>> report, lines = meshbool.dask.tiled_cutfill(meshbool.pit(), meshbool.terrain(), tile=250.0)
>>> whole, _ = meshbool.cutfill(meshbool.pit(), meshbool.terrain())
>>> abs(report["cut"] - whole["cut"]) <= 1e-9 * whole["cut"]
True
"""

from __future__ import annotations

import math
import os
import time
from typing import Any, Dict, Iterable, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import SCHEMA, Curves, Mesh, Polyline, _parts, boolean, cutfill, orient, read, write

try:
    import dask
    import distributed
except ImportError as e:  # pragma: no cover - the extra is not installed
    raise ImportError(
        "meshbool.dask needs Dask: pip install 'meshbool[dask]' (dask[distributed])"
    ) from e

__all__ = ["Failure", "map_boolean", "tiled_cutfill", "tiled_cutfill_many"]

#: A mesh as the functions here take it: a path read where the work runs, or a mesh.
MeshOrPath = Union[str, "os.PathLike[str]", Mesh, Any]


class Failure(NamedTuple):
    """A task that failed, in its place among the results: the index of its input and the
    error's text (``"ValueError: A: 12 non-manifold edges ..."``)."""

    index: int
    error: str


def _is_path(x: Any) -> bool:
    return isinstance(x, (str, os.PathLike))


def _mesh(x: MeshOrPath) -> Any:
    return read(os.fspath(x)) if _is_path(x) else x


def _stem(x: MeshOrPath, side: str) -> str:
    return os.path.splitext(os.path.basename(os.fspath(x)))[0] if _is_path(x) else side


def _current_client(client: Optional[Any]) -> Optional[Any]:
    if client is not None:
        return client
    try:
        return distributed.get_client()
    except ValueError:
        return None


def _one_boolean(
    index: int, a: MeshOrPath, b: MeshOrPath, op: str, out: Optional[str], options: dict
) -> Union[Mesh, str, Failure]:
    """One pair's boolean, on a worker: the result, the path written, or the failure."""
    try:
        result = boolean(_mesh(a), _mesh(b), op, **options)
        if out is None:
            return result
        folder = os.path.dirname(out)
        if folder:
            os.makedirs(folder, exist_ok=True)
        write(out, result)
        return out
    except Exception as e:  # every failure becomes its pair's value
        return Failure(index, f"{type(e).__name__}: {e}")


def _run(client: Optional[Any], fn: Any, calls: List[tuple], progress: bool) -> list:
    """``fn(*args)`` for each of ``calls``, on ``client`` (or Dask's local threads), in
    order."""
    if client is None:
        return list(dask.compute(*[dask.delayed(fn)(*args) for args in calls], scheduler="threads"))
    futures = [client.submit(fn, *args, pure=False) for args in calls]
    if progress:
        distributed.progress(futures)
    return client.gather(futures)


def map_boolean(
    pairs: Iterable[Tuple[MeshOrPath, MeshOrPath]],
    op: str,
    client: Optional[Any] = None,
    *,
    out: Optional[str] = None,
    progress: bool = False,
    threads: Optional[int] = 1,
    **options: Any,
) -> List[Union[Mesh, str, Failure]]:
    """The boolean ``op`` of each pair ``(a, b)``, one Dask task per pair: a list in the
    pairs' order of the results (:class:`meshbool.Mesh`, with their reports), or, with
    ``out``, of the paths written. A pair that fails gives a :class:`Failure` in its place.

    ``a`` and ``b`` are paths (read on the worker) or meshes (sent to it). ``out`` is a
    pattern of the files to write, with ``{i}`` (the pair's index), ``{a}`` and ``{b}``
    (the inputs' file names without extension, or ``a`` and ``b`` for meshes), e.g.
    ``"out/{a}-minus-{b}.ply"``; folders are made as needed. ``threads``: the library's
    threads per task (1 by default: the cluster's workers run tasks side by side);
    ``None`` for all the worker's cores. The other keywords are :func:`meshbool.boolean`'s
    (``force``, ``snap``, ...). ``progress``: Dask's progress bar (with a client).
    """
    pairs = list(pairs)
    if out is not None and len(pairs) > 1 and "{" not in out:
        raise ValueError(f"out {out!r} would name every result alike: put {{i}}, {{a}} or {{b}} in it")
    options = dict(options, threads=threads)
    calls = []
    for i, (a, b) in enumerate(pairs):
        target = None if out is None else out.format(i=i, a=_stem(a, "a"), b=_stem(b, "b"))
        calls.append((i, a, b, op, target, options))
    return _run(_current_client(client), _one_boolean, calls, progress)


def _submesh(v: np.ndarray, f: np.ndarray, rows: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Triangles ``rows`` of ``(v, f)`` with the vertices they use, in their order."""
    faces = f[rows]
    used, inverse = np.unique(faces, return_inverse=True)
    return v[used], inverse.reshape(faces.shape).astype(np.uint32)


def _plan_area(corners: np.ndarray) -> float:
    """The triangles' areas in plan, each taken positive (as the library measures a
    surface's plan area)."""
    e1, e2 = corners[:, 1, :2] - corners[:, 0, :2], corners[:, 2, :2] - corners[:, 0, :2]
    return float(0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]).sum())


def _tile_cutfill(
    dv: np.ndarray, df: np.ndarray, tv: np.ndarray, tf: np.ndarray, threads: Optional[int]
) -> Tuple[dict, List[Tuple[np.ndarray, bool]]]:
    """One tile's cut and fill, on a worker: the report and the zero lines."""
    report, lines = cutfill((dv, df), (tv, tf), threads=threads)
    return report, [(p.points, p.closed) for p in lines]


def _chained(lines: Sequence[Tuple[np.ndarray, bool]]) -> List[Polyline]:
    """Polylines joined where one ends exactly where another does (the tiles' pieces of
    one zero line meet at the same point, computed from the same triangles); ends where
    one, three or more pieces meet stay ends."""
    closed = [Polyline(p, True) for p, c in lines if c]
    chains = [p for p, c in lines if not c and len(p) > 0]
    ends: Dict[tuple, List[Tuple[int, int]]] = {}
    for k, p in enumerate(chains):
        ends.setdefault(tuple(p[0]), []).append((k, 0))
        ends.setdefault(tuple(p[-1]), []).append((k, 1))
    used = [False] * len(chains)

    def tip(k: int, end: int) -> tuple:
        return tuple(chains[k][0 if end == 0 else -1])

    def walk(k: int, start_end: int) -> Tuple[np.ndarray, bool]:
        # From chain k's end `start_end`, on through every point where exactly two meet.
        parts, first = [], tip(k, start_end)
        while True:
            used[k] = True
            p = chains[k] if start_end == 0 else chains[k][::-1]
            parts.append(p if not parts else p[1:])
            tail = tuple(p[-1])
            nxt = [e for e in ends[tail] if not used[e[0]]]
            if len(ends[tail]) != 2 or not nxt:
                points = np.concatenate(parts)
                if tail == first and len(ends[tail]) == 2:
                    return points[:-1], True  # a loop: its first point not repeated
                return points, False
            k, start_end = nxt[0]

    out = list(closed)
    for k in range(len(chains)):
        for end in (0, 1):
            if not used[k] and len(ends[tip(k, end)]) != 2:
                out.append(Polyline(*walk(k, end)))
    for k in range(len(chains)):
        if not used[k]:
            out.append(Polyline(*walk(k, 0)))
    return out


def tiled_cutfill(
    design: MeshOrPath,
    topo: MeshOrPath,
    tile: float,
    client: Optional[Any] = None,
    *,
    threads: Optional[int] = 1,
    progress: bool = False,
) -> Tuple[dict, Curves]:
    """:func:`meshbool.cutfill` of ``design`` and ``topo`` (paths or meshes), computed in
    square tiles of side ``tile`` (in plan, from the design's lowest x and y), one Dask task
    per tile holding design triangles: the report and the zero lines, as
    :func:`meshbool.cutfill` gives them for the whole.

    Both surfaces are faced up first (``faced_up`` counts the triangles turned, as in the
    whole's report). ``cut``, ``fill``, ``net``, ``common_plan_area`` and
    ``zero_line_length`` are the tiles' sums; ``design_plan_area`` and
    ``topo_plan_area`` are the surfaces' own; the zero lines are the tiles' pieces joined
    where they meet (``zero_lines`` counts them). The report adds ``tiles`` (the tasks
    run). ``threads``: the library's threads per task (1 by default). A design or
    topography without triangles raises ``ValueError``, as the whole's call does.
    """
    return tiled_cutfill_many([design], topo, tile, client, threads=threads, progress=progress)[0]


def tiled_cutfill_many(
    designs: Iterable[MeshOrPath],
    topo: MeshOrPath,
    tile: float,
    client: Optional[Any] = None,
    *,
    threads: Optional[int] = 1,
    progress: bool = False,
) -> List[Tuple[dict, Curves]]:
    """:func:`tiled_cutfill` of each of ``designs`` against one ``topo`` (hundreds of pit
    designs against a survey): the topography is faced up and indexed once, and every
    design's tiles go to the cluster as one batch. A list of ``(report, lines)`` in the
    designs' order; each report's ``seconds`` is the whole call's."""
    if not (isinstance(tile, (int, float)) and math.isfinite(tile) and tile > 0):
        raise ValueError(f"tile must be a finite size > 0, got {tile!r}")
    start = time.perf_counter()
    ground = _Ground(orient(_mesh(topo), "z-up"))
    plans = [_plan(orient(_mesh(d), "z-up"), ground, tile, threads) for d in designs]
    calls = [c for p in plans for c in p.calls]
    results = iter(_run(_current_client(client), _tile_cutfill, calls, progress))
    out = []
    for p in plans:
        report = p.report
        lines: List[Tuple[np.ndarray, bool]] = []
        for _ in p.calls:
            r, tile_lines = next(results)
            for key in ("cut", "fill", "common_plan_area", "zero_line_length"):
                report[key] += r[key]
            lines.extend(tile_lines)
        report["net"] = report["cut"] - report["fill"]
        joined = _chained(lines)
        report["zero_lines"] = len(joined)
        report["tiles"] = len(p.calls)
        out.append((report, Curves(joined)))
    for report, _ in out:
        report["seconds"] = time.perf_counter() - start
    return out


class _Ground:
    """The topography faced up, with its triangles' corners and boxes in plan."""

    def __init__(self, up: Mesh) -> None:
        self.flipped = up.report["flipped"]
        self.v, self.f = _parts(up)
        if len(self.f) == 0:
            raise ValueError("topography: no triangles; cut and fill need two surfaces")
        self.corners = self.v[self.f]
        self.lo = self.corners[:, :, :2].min(axis=1)
        self.hi = self.corners[:, :, :2].max(axis=1)


class _Plan(NamedTuple):
    """One design's tasks and its report before the tiles' sums."""

    calls: List[tuple]
    report: Dict[str, Any]


def _plan(d_up: Mesh, ground: _Ground, tile: float, threads: Optional[int]) -> _Plan:
    """The tasks of design ``d_up`` (faced up) against ``ground``: the design's triangles by
    the tile of their centroid, each tile with the topography's triangles whose boxes meet
    its triangles'."""
    dv, df = _parts(d_up)
    if len(df) == 0:
        raise ValueError("design: no triangles; cut and fill need two surfaces")
    corners = dv[df]  # (m, 3, 3)
    origin = dv[:, :2].min(axis=0)
    cell = np.floor((corners[:, :, :2].mean(axis=1) - origin) / tile).astype(np.int64)
    d_lo, d_hi = corners[:, :, :2].min(axis=1), corners[:, :, :2].max(axis=1)
    # The topography's triangles that can meet a design triangle (their boxes meet the
    # design's), by every tile their boxes meet (a triangle larger than a tile is in
    # several); a tile's design triangles may reach out of it, so a task looks in every
    # tile its triangles' box meets.
    t_lo, t_hi = ground.lo, ground.hi
    near_design = np.all(t_lo <= d_hi.max(axis=0), axis=1) & np.all(t_hi >= d_lo.min(axis=0), axis=1)
    cand = np.nonzero(near_design)[0]
    c_lo = np.floor((t_lo[cand] - origin) / tile).astype(np.int64)
    c_hi = np.floor((t_hi[cand] - origin) / tile).astype(np.int64)
    sx, sy = c_hi[:, 0] - c_lo[:, 0] + 1, c_hi[:, 1] - c_lo[:, 1] + 1
    counts = sx * sy
    rep = np.repeat(np.arange(len(cand)), counts)
    k = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
    t_cells = np.stack([c_lo[rep, 0] + k // sy[rep], c_lo[rep, 1] + k % sy[rep]], axis=1)
    topo_in = dict(_groups(t_cells, cand[rep]))
    calls = []
    for _, rows in _groups(cell, np.arange(len(df))):
        lo, hi = d_lo[rows].min(axis=0), d_hi[rows].max(axis=0)
        a, b = np.floor((lo - origin) / tile).astype(np.int64), np.floor((hi - origin) / tile).astype(np.int64)
        found = [
            topo_in[(x, y)]
            for x in range(a[0], b[0] + 1)
            for y in range(a[1], b[1] + 1)
            if (x, y) in topo_in
        ]
        if not found:
            continue
        near = np.unique(np.concatenate(found))
        near = near[np.all(t_lo[near] <= hi, axis=1) & np.all(t_hi[near] >= lo, axis=1)]
        if len(near) == 0:
            continue
        calls.append((*_submesh(dv, df, rows), *_submesh(ground.v, ground.f, near), threads))
    report: Dict[str, Any] = {
        "schema": SCHEMA,
        "cut": 0.0,
        "fill": 0.0,
        "net": 0.0,
        "design_plan_area": _plan_area(corners),
        "topo_plan_area": _plan_area(ground.corners),
        "common_plan_area": 0.0,
        "zero_lines": 0,
        "zero_line_length": 0.0,
        "faced_up": [d_up.report["flipped"], ground.flipped],
    }
    return _Plan(calls, report)


def _groups(keys: np.ndarray, rows: np.ndarray) -> Iterable[Tuple[Tuple[int, int], np.ndarray]]:
    """``rows`` grouped by their ``keys`` (pairs of cell indices, one row each), in the
    order of the keys."""
    if len(rows) == 0:
        return
    lo = keys.min(axis=0)
    width = int(keys[:, 1].max() - lo[1]) + 1
    flat = (keys[:, 0] - lo[0]) * width + (keys[:, 1] - lo[1])
    order = np.argsort(flat, kind="stable")
    flat = flat[order]
    starts = np.flatnonzero(np.r_[True, flat[1:] != flat[:-1]])
    ends = np.r_[starts[1:], len(flat)]
    for a, b in zip(starts, ends):
        x, y = divmod(int(flat[a]), width)
        yield (x + int(lo[0]), y + int(lo[1])), rows[order[a:b]]
