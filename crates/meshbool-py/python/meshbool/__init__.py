"""meshbool: exact boolean operations on triangle meshes, closed solids and open surfaces.

Numpy in, numpy out. A mesh is any of: a :class:`Mesh`, an object with ``.vertices`` and
``.faces`` (a ``trimesh.Trimesh``), or a ``(vertices, faces)`` tuple; vertices are
``float64 (n, 3)``, faces integer ``(m, 3)`` indices into them.

>>> import numpy as np, meshbool
>>> cube = meshbool.box([0, 0, 0], [1, 1, 1])
>>> other = meshbool.box([0.5, 0.5, 0.5], [1.5, 1.5, 1.5])
>>> union = meshbool.boolean(cube, other, "union")
>>> union.volume, union.is_closed
(1.875, True)

Every call releases the GIL while it works, and Ctrl-C stops a long one (``boolean``,
``boolean_many``, ``split``, ``resolve``, ``cutfill`` on 32k triangles or more): the
library stops at its next stage and ``KeyboardInterrupt`` is raised. Errors raise
``ValueError`` (bad geometry, arguments or file content) or ``OSError`` (files), with the
library's message. The reports are the dicts the ``meshbool`` command line prints with
``--json``.
"""

from __future__ import annotations

import json
import os
from typing import Any, Iterable, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _native

__all__ = [
    "Mesh",
    "Operand",
    "Split",
    "Polyline",
    "Curves",
    "boolean",
    "boolean_many",
    "split",
    "pick",
    "curves",
    "classify",
    "POINT_CLASSES",
    "cutfill",
    "repair",
    "resolve",
    "envelope",
    "orient",
    "close",
    "csg",
    "CsgCache",
    "read",
    "write",
    "box",
    "terrain",
    "pit",
    "OPERATIONS",
    "GROUPS",
    "SCHEMA",
    "__version__",
]

__version__ = _native.VERSION
#: The version of the reports (their ``"schema"`` key).
SCHEMA = _native.SCHEMA
#: Operation names :func:`boolean` takes (``"intersect"`` and ``"subtract"`` as well).
OPERATIONS = ("union", "intersection", "difference", "reverse_difference")
#: The groups of a split.
GROUPS = (
    "a_in_b",
    "a_out_b",
    "b_in_a",
    "b_out_a",
    "a_on_b_same",
    "a_on_b_opposite",
    "b_on_a_same",
    "b_on_a_opposite",
)


def _arrays(vertices: Any, faces: Any) -> Tuple[np.ndarray, np.ndarray]:
    """Vertices as C-contiguous float64 (n, 3), faces as C-contiguous uint32 (m, 3)."""
    v = np.asarray(vertices)
    f = np.asarray(faces)
    if v.size == 0:
        v = v.reshape(0, 3)
    if f.size == 0:
        f = f.reshape(0, 3)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), got {v.shape}")
    if f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"faces must have shape (m, 3), got {f.shape}")
    if not (np.issubdtype(v.dtype, np.floating) or np.issubdtype(v.dtype, np.integer)):
        raise ValueError(f"vertices must be numbers, got dtype {v.dtype}")
    if f.size and not np.issubdtype(f.dtype, np.integer):
        raise ValueError(f"faces must be integers, got dtype {f.dtype}")
    if f.size and (f.min() < 0 or f.max() > np.iinfo(np.uint32).max):
        raise ValueError(
            f"face indices must be in 0..{np.iinfo(np.uint32).max}, got {f.min()}..{f.max()}"
        )
    return _native_layout(v, f)


def _native_layout(v: np.ndarray, f: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """The arrays as the library reads them: C-contiguous and aligned (arrays rebuilt from
    a transport's buffers, as Dask's, may not be), float64 and uint32; copied only where
    they are not."""
    return (
        np.require(v, dtype=np.float64, requirements=["C", "A"]),
        np.require(f, dtype=np.uint32, requirements=["C", "A"]),
    )


def _parts(mesh: Any) -> Tuple[np.ndarray, np.ndarray]:
    """The arrays of anything that is a mesh."""
    if isinstance(mesh, Mesh):
        return _native_layout(mesh.vertices, mesh.faces)
    if hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
        return _arrays(mesh.vertices, mesh.faces)
    if isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        return _arrays(mesh[0], mesh[1])
    raise ValueError(
        "expected a mesh: a meshbool.Mesh, an object with .vertices and .faces, "
        f"or a (vertices, faces) tuple; got {type(mesh).__name__}"
    )


class Mesh:
    """A triangle mesh: ``vertices`` float64 (n, 3), ``faces`` uint32 (m, 3).

    Indices are checked when the mesh is made (``ValueError`` naming the first bad face);
    coordinates may be anything, and operations that need finite ones check them.
    Results of operations carry ``report`` (the command line's ``--json`` dict) and,
    for booleans, ``provenance``.
    """

    __slots__ = ("vertices", "faces", "_provenance", "_report", "_pending")

    def __init__(self, vertices: Any, faces: Any) -> None:
        v, f = _arrays(vertices, faces)
        if f.size and f.max() >= len(v):
            bad = int(np.argmax((f >= len(v)).any(axis=1)))
            raise ValueError(
                f"invalid mesh at triangle {bad}: vertex index out of range in "
                f"{f[bad].tolist()} (the mesh has {len(v)} vertices)"
            )
        self.vertices: np.ndarray = v
        self.faces: np.ndarray = f
        self._provenance: Optional[dict] = None
        self._report: Optional[dict] = None
        self._pending: Any = None

    @classmethod
    def _from(cls, v: np.ndarray, f: np.ndarray, report: Optional[str] = None) -> "Mesh":
        m = cls.__new__(cls)
        m.vertices, m.faces = v, f
        m._report = json.loads(report) if report is not None else None
        m._pending = None
        m._provenance = None
        return m

    @property
    def provenance(self) -> Optional[dict]:
        """Where each triangle came from, as a dict of arrays (see the operation that made
        the mesh; ``None`` for a mesh no operation made). A boolean's provenance is made
        on first use."""
        if self._provenance is None and self._pending is not None:
            source, triangle, flipped = self._pending.provenance()
            self._provenance = {"source": source, "triangle": triangle, "flipped": flipped}
        return self._provenance

    @provenance.setter
    def provenance(self, value: Optional[dict]) -> None:
        self._provenance = value

    @property
    def report(self) -> Optional[dict]:
        """What made this mesh reported: the dict the command line prints with ``--json``
        (``None`` for a mesh no operation made). A boolean's report is measured on first
        use."""
        if self._report is None and self._pending is not None:
            self._report = json.loads(self._pending.report(self.vertices, self.faces))
        return self._report

    def _measures(self) -> Tuple[float, float, bool]:
        return _native.measures(self.vertices, self.faces)

    @property
    def volume(self) -> float:
        """Signed volume (positive for a closed mesh facing outward)."""
        return self._measures()[0]

    @property
    def area(self) -> float:
        """Surface area."""
        return self._measures()[1]

    @property
    def is_closed(self) -> bool:
        """True when the mesh has triangles and neither boundary nor non-manifold edges."""
        return self._measures()[2]

    @property
    def assumed(self) -> list:
        """What a boolean's result assumes (skipped checks, problems taken as given)."""
        if self._pending is not None:
            return list(self._pending.assumed())
        return list((self.report or {}).get("assumed", []))

    def stats(self) -> dict:
        """Every measure: the dict of ``meshbool info --json`` (without ``file``)."""
        report = json.loads(_native.info(self.vertices, self.faces))
        report.pop("file", None)
        return report

    def to_trimesh(self) -> Any:
        """The mesh as a ``trimesh.Trimesh`` (trimesh must be installed; not processed)."""
        import trimesh

        return trimesh.Trimesh(vertices=self.vertices, faces=self.faces, process=False)

    def __len__(self) -> int:
        return len(self.faces)

    def __repr__(self) -> str:
        return f"meshbool.Mesh({len(self.vertices)} vertices, {len(self.faces)} faces)"

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        # Pickled as its arrays, report and provenance (made now where they are pending),
        # so that a result crosses process boundaries (multiprocessing, Dask workers).
        return (_rebuilt, (self.vertices, self.faces, self.report, self.provenance))


def _rebuilt(
    vertices: np.ndarray, faces: np.ndarray, report: Optional[dict], provenance: Optional[dict]
) -> Mesh:
    """A pickled :class:`Mesh` again."""
    m = Mesh._from(*_native_layout(vertices, faces))
    m._report, m._provenance = report, provenance
    return m


def box(lo: Sequence[float], hi: Sequence[float]) -> Mesh:
    """An axis-aligned box from ``lo`` to ``hi``: 8 vertices, 12 outward-facing triangles."""
    lo, hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    corners = np.array(
        [[(hi if i & (1 << k) else lo)[k] for k in range(3)] for i in range(8)]
    )
    faces = [
        [0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
        [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5],
    ]  # fmt: skip
    return Mesh(corners, faces)


def _pair(value: Any, name: str, kind: type) -> Tuple[Any, Any]:
    """One value (for both) or two, as ``kind``; ``ValueError`` otherwise."""
    values = [value] * 2 if np.ndim(value) == 0 else list(np.asarray(value).ravel())
    if len(values) != 2:
        raise ValueError(f"{name} takes one value or two, got {len(values)}")
    if kind is int:
        return _count(values[0], name), _count(values[1], name)
    return float(values[0]), float(values[1])


def _point(value: Sequence[float], name: str) -> Tuple[float, float, float]:
    """Three numbers x, y, z; ``ValueError`` otherwise."""
    p = [float(v) for v in np.asarray(value, dtype=np.float64).ravel()]
    if len(p) != 3:
        raise ValueError(f"{name} takes three numbers x, y, z, got {len(p)}")
    return p[0], p[1], p[2]


def _count(value: Any, name: str) -> int:
    """A whole number, 0 or more (the native side's unsigned types); ``ValueError``
    otherwise."""
    if int(value) != value or value < 0:
        raise ValueError(f"{name} must be a whole number, 0 or more, got {value!r}")
    return int(value)


def terrain(
    center: Sequence[float] = (0.0, 0.0, 0.0),
    size: Union[float, Sequence[float]] = (1000.0, 1000.0),
    cells: Union[int, Sequence[int]] = (100, 100),
    relief: float = 40.0,
    seed: int = 1,
) -> Mesh:
    """A seeded, realistic terrain (``meshbool make terrain``): an open height field over
    the rectangle ``center[:2] ± size / 2`` in ``cells`` (x, y; one number for both) of
    two triangles, facing +z, with hills, hollows, a regional slope and a little
    roughness; its lowest vertex at ``center[2] − relief / 2``, its highest at
    ``center[2] + relief / 2``. The same ``seed`` (0 to 2⁶⁴ − 1) gives the same
    coordinates, bit for bit, on every platform. ``2 · cells[0] · cells[1]`` triangles,
    one boundary loop. With the defaults it is crossed by the default :func:`pit` along
    one closed curve. ``ValueError`` for a non-positive size, zero cells, a negative
    relief. ``report`` is the ``meshbool make terrain --json`` dict.

    >>> t = meshbool.terrain()
    >>> len(t.faces), t.report["boundary_edges"], t.report["bbox"]["max"][2]
    (20000, 400, 20.0)
    """
    seed = _count(seed, "seed")
    if seed >= 1 << 64:
        raise ValueError(f"seed must be below 2**64, got {seed}")
    cx, cy = _pair(cells, "cells", int)
    args = (_point(center, "center"), _pair(size, "size", float), (cx, cy))
    return Mesh._from(*_native.terrain(*args, float(relief), seed))


def pit(
    center: Sequence[float] = (0.0, 0.0, 60.0),
    radius: Union[float, Sequence[float]] = (220.0, 160.0),
    depth: float = 140.0,
    benches: int = 5,
    berm: float = 8.0,
    segments: int = 64,
) -> Mesh:
    """An open-pit design shell (``meshbool make pit``): a benched bowl, elliptical in plan
    with semi-axes ``radius`` (x, y; one number for a circle) at the rim, the rim at
    ``center[2]``, the floor ``depth`` below; ``benches`` faces at a 2:1 batter
    separated by flat berms ``berm`` wide, then a flat floor, in rings of ``segments``
    vertices. Open (the rim its one boundary loop), single-valued in plan, facing up.
    With the defaults, its rim stands above the default :func:`terrain` all round and
    its floor below it. ``ValueError`` when the faces and berms (``depth / 2 + (benches
    − 1) · berm`` in from the rim) do not fit in the radius, or for other bad values.
    ``report`` is the ``meshbool make pit --json`` dict.

    >>> p = meshbool.pit()
    >>> len(p.faces), len(p.vertices), p.report["bbox"]["min"]
    (1216, 641, [-220.0, -160.0, -80.0])
    """
    args = (_point(center, "center"), _pair(radius, "radius", float), float(depth))
    counts = (_count(benches, "benches"), float(berm), _count(segments, "segments"))
    return Mesh._from(*_native.pit(*args, *counts))


MeshLike = Union[Mesh, Tuple[Any, Any], Any]


class Operand:
    """A mesh welded and checked once, for many booleans: :func:`boolean` takes it in
    place of a mesh and skips its weld and checks (what the door fixes, it fixed here:
    see :func:`boolean` for the flags). ``report`` is what the checks found (the
    ``operands`` entry of a boolean's report); ``mesh`` the checked mesh (welded, and the
    solid it encloses when it was resolved).

    ``ValueError`` when a check finds a problem and ``force`` is off, as :func:`boolean`
    raises it.
    """

    __slots__ = ("_native",)

    def __init__(
        self,
        mesh: MeshLike,
        *,
        name: str = "mesh",
        force: bool = False,
        self_check: bool = True,
        resolve: bool = True,
        orient: bool = True,
        threads: Optional[int] = None,
    ) -> None:
        v, f = _parts(mesh)
        self._native = _native.Operand(v, f, name, force, self_check, resolve, orient, threads)

    @property
    def report(self) -> dict:
        """What the checks found."""
        return json.loads(self._native.report())

    @property
    def mesh(self) -> "Mesh":
        """The checked mesh."""
        return Mesh._from(*self._native.arrays())


def boolean(
    a: MeshLike,
    b: MeshLike,
    op: str,
    *,
    force: bool = False,
    self_check: bool = True,
    resolve: bool = True,
    orient: bool = True,
    threads: Optional[int] = None,
    keep_nonmanifold: bool = False,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    coplanar_refinement: bool = False,
) -> Mesh:
    """The boolean ``op`` of ``a`` and ``b``.

    ``op``: ``"union"``, ``"intersection"`` (``"intersect"``), ``"difference"``
    (``"subtract"``: a − b) or ``"reverse_difference"`` (b − a). Closed meshes must face
    outward; an open surface's inside is behind it (the side its normals point away from).

    Inputs are checked. What the door can fix it fixes, with a line in ``result.assumed``:
    inconsistently oriented triangles are made consistent (each component facing as most
    of its triangles do; ``orient=False`` refuses instead), inside-out closed parts are
    reversed, and self-intersecting closed parts are resolved into the solid they enclose
    (see :func:`resolve`; ``resolve=False`` refuses instead). What it cannot fix
    (non-manifold edges, an orientation that cannot be made consistent, open
    self-crossing surfaces) raises ``ValueError`` unless ``force`` (then ``assumed`` lists
    what was taken as given). ``self_check=False``
    skips the self-intersection check (for inputs known to be clean). ``threads``: worker
    threads (default all cores). ``keep_nonmanifold``: keep edges and vertices where the
    result's solids touch instead of splitting them. ``snap``: a tolerance D > 0 cleans
    the result (edges shorter than D collapsed, needles with an altitude below D removed)
    where that keeps it manifold, turns no triangle over, makes no self-intersection and
    moves no vertex more than D; ``report["snap"]`` says what it did (0, the default: the
    exact result). ``keep_seam_points``: keep every seam point of the exact arrangement;
    by default seam points where the result is flat or straight are removed and zero-area
    triangles made by rounding collapsed or flipped away, no surface moving
    (``report["cleanup"]``). ``coplanar_refinement``: cut coplanar overlaps (shared
    faces) along every edge of either input that crosses them, so that the result's faces
    there hold the common refinement of both triangulations (as the reference JS
    library's do); by default coplanar regions meet along their boundaries only.

    ``a`` and ``b`` may be :class:`Operand` s, welded and checked before (the flags
    above then apply only to a plain mesh beside one): repeated booleans on one mesh
    skip its weld and checks.

    Returns a :class:`Mesh` with ``report`` (the ``--json`` dict) and ``provenance``
    (a dict of arrays: ``source`` 0 for a / 1 for b, ``triangle`` in that input,
    ``flipped``).
    """
    a_operand, b_operand = isinstance(a, Operand), isinstance(b, Operand)
    if a_operand or b_operand:
        if not (a_operand and b_operand):
            flags = dict(force=force, self_check=self_check, resolve=resolve, orient=orient,
                         threads=threads)
            a = a if a_operand else Operand(a, name="A", **flags)
            b = b if b_operand else Operand(b, name="B", **flags)
        v, f, pending = _native.boolean_operands(
            a._native, b._native, op, threads, keep_nonmanifold, float(snap), keep_seam_points,
            coplanar_refinement,
        )
    else:
        av, af = _parts(a)
        bv, bf = _parts(b)
        v, f, pending = _native.boolean(
            av, af, bv, bf, op, force, self_check, resolve, orient, threads,
            keep_nonmanifold, float(snap), keep_seam_points, coplanar_refinement,
        )
    out = Mesh._from(v, f)
    out._pending = pending
    return out


def boolean_many(
    meshes: Iterable[MeshLike],
    op: str = "union",
    *,
    force: bool = False,
    self_check: bool = True,
    resolve: bool = True,
    orient: bool = True,
    threads: Optional[int] = None,
    keep_nonmanifold: bool = False,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    one_arrangement: bool = False,
) -> Mesh:
    """The union (``op="union"``) or intersection (``"intersection"``) of any number of
    meshes in one call: pairwise booleans in a balanced tree, in parallel, rather than a
    chain; or the first mesh less all the others (``"difference"``: the others united,
    then one difference, as ``meshbool difference A B C``). Checks and options as for :func:`boolean`. The result's ``provenance`` has
    ``input`` (position in ``meshes``) and ``triangle`` (in that input).

    ``one_arrangement=True``: more than two closed meshes are cut along one another all at
    once and each piece is kept by the exact winding numbers on its sides, exact to the end
    (no intermediate result rounded) but slower than the tree; ``report["combined"]``
    says which was used."""
    parts = [_parts(m) for m in meshes]
    v, f, input, triangle, report = _native.boolean_many(
        parts, op, force, self_check, resolve, orient, threads, keep_nonmanifold,
        float(snap), keep_seam_points, one_arrangement,
    )
    out = Mesh._from(v, f, report)
    out.provenance = {"input": input, "triangle": triangle}
    return out


class Split:
    """Two meshes cut along their intersection: groups (``a_in_b``, ``a_out_b``,
    ``b_in_a``, ``b_out_a`` and the coplanar ``a_on_b_same``, ``a_on_b_opposite``,
    ``b_on_a_same``, ``b_on_a_opposite``) as attributes (an empty :class:`Mesh` where a
    group is empty), their connected components, and picking pieces back together."""

    __slots__ = ("_native",)

    def __init__(self, native: Any) -> None:
        self._native = native

    @property
    def groups(self) -> list:
        """The names of the non-empty groups."""
        return list(self._native.groups())

    def group(self, name: str) -> Mesh:
        """A group's triangles (an empty mesh where the group is empty)."""
        arrays = self._native.group(name)
        if arrays is None:
            return Mesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.uint32))
        return Mesh._from(*arrays)

    def __getattr__(self, name: str) -> Mesh:
        if name in GROUPS:
            return self.group(name)
        raise AttributeError(name)

    def components(self, group: str) -> list:
        """A group's connected components, largest first (``GROUP#k`` in :meth:`pick`)."""
        return [Mesh._from(v, f) for v, f in self._native.components(group)]

    def pick(
        self,
        *pieces: str,
        op: Optional[str] = None,
        keep_nonmanifold: bool = False,
        snap: float = 0.0,
    ) -> Mesh:
        """Merges pieces into one welded mesh: ``"a_out_b"``, ``"b_in_a:flip"``,
        ``"a_in_b#2"`` (group, optional ``#component``, optional ``:flip``). A piece may be
        named once. ``op="difference"`` (or another boolean) picks the pieces that boolean
        keeps instead: its result, from the pieces. Where pieces touch along an edge or at
        a vertex the result is made manifold unless ``keep_nonmanifold``. ``snap``: a
        tolerance D > 0 cleans the merged mesh where its pieces meet, as
        :func:`boolean`'s ``snap`` does (``report["snap"]``)."""
        if op is not None:
            if pieces:
                raise ValueError("name pieces or an op, not both")
            groups = set(self.groups)
            pieces = tuple(
                p for p in _native.pieces_for_op(op) if p.split(":")[0] in groups
            )
        if len(pieces) == 1 and not isinstance(pieces[0], str):
            pieces = tuple(pieces[0])
        v, f, report = self._native.pick(list(pieces), keep_nonmanifold, float(snap))
        return Mesh._from(v, f, report)

    def report(self, format: str = "ply") -> dict:
        """What the split holds (the manifest ``write`` would write in ``format``)."""
        return json.loads(self._native.report(format))

    def write(self, directory: str, format: str = "ply") -> dict:
        """Writes every group and component and ``manifest.json`` (returned) to a
        directory, for ``meshbool pick`` or :func:`pick` from the command line."""
        return json.loads(self._native.write(str(directory), format))

    def __repr__(self) -> str:
        return f"meshbool.Split(groups={self.groups})"


def split(
    a: MeshLike,
    b: MeshLike,
    *,
    force: bool = False,
    self_check: bool = True,
    resolve: bool = True,
    orient: bool = True,
    threads: Optional[int] = None,
    merge_small: int = 0,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    coplanar_refinement: bool = False,
) -> Split:
    """Splits ``a`` and ``b`` along their intersection into groups and components.
    Checks as for :func:`boolean`; ``merge_small`` folds components of fewer triangles
    into the nearest larger one of their group. ``snap``: a tolerance D > 0 cleans all
    groups together where the split cut (as :func:`boolean`'s ``snap``), so that any
    pick of them is closed where the exact pick is (``report()["snap"]``).
    ``keep_seam_points``: keep every seam point of the exact arrangement (by default
    those where the seam runs straight through flat faces of both meshes go, no group
    changing shape; ``report()["cleanup"]``). ``coplanar_refinement``: the coplanar
    groups hold the common refinement of both triangulations (as :func:`boolean`'s)."""
    av, af = _parts(a)
    bv, bf = _parts(b)
    return Split(
        _native.split(
            av, af, bv, bf, force, self_check, resolve, orient, threads, merge_small,
            float(snap), keep_seam_points, coplanar_refinement,
        )
    )


def pick(
    pieces: Iterable[Any], *, keep_nonmanifold: bool = False, snap: float = 0.0
) -> Mesh:
    """Merges meshes into one, welding exactly equal positions: ``pieces`` are meshes or
    ``(mesh, flip)`` pairs. ``snap``: a tolerance D > 0 cleans the result where the
    pieces meet (see :meth:`Split.pick`)."""
    parts = []
    for p in pieces:
        if isinstance(p, tuple) and len(p) == 2 and isinstance(p[1], (bool, np.bool_)):
            mesh, flip = p
        else:
            mesh, flip = p, False
        v, f = _parts(mesh)
        parts.append((v, f, bool(flip)))
    v, f, report = _native.pick(parts, keep_nonmanifold, float(snap))
    return Mesh._from(v, f, report)


class Polyline(NamedTuple):
    """An intersection curve: its points (k, 3) and whether it closes on itself."""

    points: np.ndarray
    closed: bool


class Curves(list):
    """The intersection curves (a list of :class:`Polyline`) with their ``report``."""

    report: dict


def curves(
    a: MeshLike,
    b: Optional[MeshLike] = None,
    *,
    with_coplanar: bool = True,
    simplify: Optional[float] = None,
    tagged: bool = False,
    coplanar_refinement: bool = False,
) -> Curves:
    """The exact intersection curves of ``a`` and ``b``, chained into polylines: closed
    loops and open chains (ending on an open surface's boundary). Without ``b``: where
    ``a`` crosses itself. ``with_coplanar=False`` leaves out segments that only bound
    shared faces. ``simplify=D`` thins the polylines (points closer than ``D`` to the last
    kept one along a line are left out). ``tagged=True`` puts every raw segment with its
    triangles in ``report["tagged_segments"]`` (``p0``, ``p1``, ``tri_a``, ``tri_b``,
    ``coplanar``). ``coplanar_refinement=True`` adds the segments where an edge of
    either mesh crosses a shared face (the common refinement there, as the reference JS
    library lists them); by default shared faces give their boundaries only."""
    av, af = _parts(a)
    lines, report = _native.curves(
        av, af, None if b is None else _parts(b), with_coplanar, simplify, tagged,
        coplanar_refinement,
    )
    out = Curves(Polyline(p, c) for p, c in lines)
    out.report = json.loads(report)
    return out


#: The classes of :func:`classify`, by their code.
POINT_CLASSES = ("outside", "inside", "on")


def classify(
    mesh: MeshLike,
    points: npt.ArrayLike,
    *,
    force: bool = False,
    threads: Optional[int] = None,
) -> Tuple[npt.NDArray[np.uint8], npt.NDArray[np.float64]]:
    """Where each of ``points`` (an ``(n, 3)`` array) lies against ``mesh``: a code per
    point — 0 outside, 1 inside, 2 exactly on the surface (decided exactly; names in
    :data:`POINT_CLASSES`) — and the winding number at each. Inside a closed mesh means
    winding number ≥ 1/2; for an open surface, behind it (winding number > 0). The mesh is
    checked as a boolean operand (``force`` takes problems as given)."""
    v, f = _parts(mesh)
    pts = np.ascontiguousarray(np.asarray(points, dtype=np.float64).reshape(-1, 3))
    classes, winding, _ = _native.classify(v, f, pts, force, threads)
    return classes, winding


def cutfill(
    design: MeshLike, topo: MeshLike, *, threads: Optional[int] = None
) -> Tuple[dict, Curves]:
    """Cut and fill between a design surface and the topography (both faced up first):
    the ``meshbool cutfill --json`` dict (``cut``, ``fill``, ``net``, plan areas, ...) and
    the lines where the surfaces meet. Volumes over the plan area both cover, from exact
    booleans of the solids under each surface."""
    dv, df = _parts(design)
    tv, tf = _parts(topo)
    report, lines = _native.cutfill(dv, df, tv, tf, threads)
    return json.loads(report), Curves(Polyline(p, c) for p, c in lines)


def resolve(
    mesh: MeshLike,
    rule: str = "positive",
    *,
    keep_nonmanifold: bool = False,
    threads: Optional[int] = None,
    snap: float = 0.0,
) -> Mesh:
    """The solid a self-overlapping mesh encloses, as a clean closed mesh: closed parts
    that cross are united, parts nested in others dropped (or kept reversed), as the fill
    rule says: ``"positive"`` (winding number ≥ 1, the union), ``"nonzero"``,
    ``"evenodd"``; a part that crosses itself is cut along its own seam. A mesh that
    cannot be given a meaning (open and crossing itself) raises ``ValueError``.
    The result's ``provenance["triangle"]`` is the input triangle of each of its
    triangles; ``report`` is the ``meshbool resolve --json`` dict. ``snap``: a
    tolerance, as for :func:`boolean`."""
    v, f = _parts(mesh)
    v, f, parent, report = _native.resolve(
        v, f, rule, keep_nonmanifold, threads, float(snap)
    )
    out = Mesh._from(v, f, report)
    out.provenance = {"triangle": parent}
    return out


def envelope(
    mesh: MeshLike, side: str = "upper", *, threads: Optional[int] = None
) -> Mesh:
    """The envelope of an open surface that folds over itself (a terrain with folds or
    overhangs): ``"upper"`` keeps what is seen from above, ``"lower"`` from below, as one
    single-valued surface faced up, exact (every triangle lies in an input triangle;
    vertical walls keep it connected where it jumps from an overhang's edge to the sheet
    under it). A closed mesh raises ``ValueError``. ``provenance["triangle"]`` is the
    input triangle of each result triangle (for a wall, the triangle it hangs from);
    ``report`` is the ``meshbool resolve --envelope SIDE --json`` dict."""
    v, f = _parts(mesh)
    v, f, parent, report = _native.envelope(v, f, side, threads)
    out = Mesh._from(v, f, report)
    out.provenance = {"triangle": parent}
    return out


def orient(mesh: MeshLike, facing: str = "majority") -> Mesh:
    """Consistent orientation, each component facing as asked: ``"majority"`` (as most of
    its triangles did), ``"z-up"`` (terrain), ``"outward"`` (closed components)."""
    v, f = _parts(mesh)
    return Mesh._from(*_native.orient(v, f, facing.replace("_", "-")))


def close(
    mesh: MeshLike,
    mode: str = "cap",
    *,
    floor_offset: float = 10.0,
    max_gap: Optional[float] = None,
) -> Mesh:
    """Closes an open mesh into a solid: ``"cap"`` (triangulate every hole), ``"stitch"``
    (join pairs of holes, at most ``max_gap`` apart), ``"curtain"`` (walls down to
    ``min z − floor_offset``, floor capped: orient the surface up first),
    ``"stitch+curtain"``."""
    v, f = _parts(mesh)
    return Mesh._from(*_native.close(v, f, mode, float(floor_offset), max_gap))


def repair(mesh: MeshLike, **config: Any) -> Mesh:
    """The repair pipeline; keyword arguments are the fields of the library's
    ``RepairConfig`` (the ``--config`` JSON of ``meshbool repair``): ``weld`` (a
    distance), ``remove_duplicates``, ``tjunctions``, ``degenerate`` (``{"min_area": ..,
    "max_aspect": ..}``), ``orient`` (``"majority"``, ``"z-up"``, ``"outward"`` or
    ``None``), ``remove_folds``, ``close`` (a :func:`close` mode), ``close_options``
    (``{"floor_offset": .., "stitch_max_gap": ..}``), ``close_gaps`` (a size), ``snap``
    (a tolerance, as for :func:`boolean`, after degenerate removal), ``gate``
    (default ``True``: a step that makes the mesh worse is undone and listed in the
    report's ``undone``) and ``gate_volume`` (the largest relative volume change of a
    closed mesh a step may make, default 0.005). Unknown keywords raise ``ValueError``.
    The report says what every step did."""
    v, f = _parts(mesh)
    return Mesh._from(*_native.repair(v, f, json.dumps(config)))


class CsgCache:
    """Results of CSG nodes by key (see :func:`csg`), kept between calls: in memory, and
    with ``dir`` also as files in that folder (created if missing), so that they outlive
    the process. After an edit, a call with the same cache computes only the edited node
    and its ancestors."""

    __slots__ = ("_native",)

    def __init__(self, dir: Optional[Union[str, "os.PathLike[str]"]] = None) -> None:
        self._native = _native.CsgCache(None if dir is None else str(dir))

    def __len__(self) -> int:
        return len(self._native)

    def clear(self) -> None:
        """Forgets the results held in memory (the folder's files stay)."""
        self._native.clear()


def _inline(node: Any, meshes: list, at: str) -> Any:
    """A copy of a scene node whose in-memory meshes (``"mesh"`` given a mesh rather than
    a path) are replaced by their index in ``meshes``, to which their arrays are appended."""
    if not isinstance(node, dict):
        raise ValueError(f"malformed CSG scene: {at}: expected an object, got {type(node).__name__}")
    out = dict(node)
    mesh = node.get("mesh")
    if mesh is not None and not isinstance(mesh, (str, os.PathLike)):
        out["mesh"] = len(meshes)
        meshes.append(_parts(mesh))
    elif isinstance(mesh, os.PathLike):
        out["mesh"] = os.fspath(mesh)
    children = node.get("children")
    if isinstance(children, list):
        out["children"] = [_inline(c, meshes, f"{at}.children[{k}]") for k, c in enumerate(children)]
    return out


def csg(
    scene: Union[dict, str, "os.PathLike[str]"],
    *,
    base: Optional[Union[str, "os.PathLike[str]"]] = None,
    cache: Optional[CsgCache] = None,
    force: bool = False,
    self_check: bool = True,
    resolve: bool = True,
    orient: bool = True,
    threads: Optional[int] = None,
    keep_nonmanifold: bool = False,
    snap: float = 0.0,
    keep_seam_points: bool = False,
) -> Mesh:
    """Evaluates a CSG document: a tree of unions, intersections and differences over mesh
    files, meshes and primitives, each node with its transform, cutters subtracted in
    differences (the format: docs/csg.md in the repository).

    ``scene``: the path of a JSON document (its mesh paths relative to its folder), or the
    document as a dict, whose ``"mesh"`` leaves may also hold meshes (a :class:`Mesh`, a
    ``trimesh.Trimesh``, a ``(vertices, faces)`` tuple) and whose paths are relative to
    ``base`` (default: the current directory). ``cache``: a :class:`CsgCache` to reuse
    results between calls (default: a fresh one). The other options are :func:`boolean`'s,
    applied to every boolean of the tree.

    Returns the root's result, with ``report``: the root's measures, ``computed`` and
    ``cached`` counts and ``nodes``, one dict per node visited (``path``, ``name``, ``kind``,
    ``source``: computed, memory or disk, measures, ``seconds``, ``notes``). Raises
    ``ValueError`` naming the node when one fails (the report is the exception's
    ``report``) and for a malformed document (saying where)."""
    meshes: list = []
    if isinstance(scene, dict):
        doc = dict(scene)
        if "root" in doc:
            doc["root"] = _inline(doc["root"], meshes, "root")
        text = json.dumps(doc)
        folder = os.fspath(base) if base is not None else os.getcwd()
    else:
        path = os.fspath(scene)
        with open(path, encoding="utf-8") as file:
            text = file.read()
        folder = os.fspath(base) if base is not None else (os.path.dirname(os.path.abspath(path)))
    cache = cache if cache is not None else CsgCache()
    arrays, report = _native.csg(
        text, folder, meshes, cache._native, force, self_check, resolve, orient, threads,
        keep_nonmanifold, float(snap), keep_seam_points,
    )
    if arrays is None:
        parsed = json.loads(report)
        failed = parsed["failed"]
        err = ValueError(f"node {failed['path']} failed: {failed['error']}")
        err.report = parsed  # type: ignore[attr-defined]
        raise err
    return Mesh._from(arrays[0], arrays[1], report)


def read(path: str, format: Optional[str] = None) -> Mesh:
    """Reads a mesh file (STL, OBJ, PLY, DXF, JSON soups), as the file has it; the format
    from its name and content unless given (``"stl"``, ``"obj"``, ``"ply"``, ...)."""
    v, f, _ = _native.read(str(path), format)
    return Mesh._from(v, f)


def write(path: str, mesh: MeshLike, format: Optional[str] = None) -> None:
    """Writes a mesh file in ``format`` or the format its name says (``.stl`` binary,
    ``.obj``, ``.ply`` binary little-endian, ``.dxf``, ``.json``)."""
    v, f = _parts(mesh)
    _native.write(str(path), v, f, format)
