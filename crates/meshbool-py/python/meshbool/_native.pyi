"""Type stubs of the extension module behind ``meshbool`` (use the package's functions)."""

from typing import List, Optional, Tuple

import numpy as np
import numpy.typing as npt

SCHEMA: int
VERSION: str

F64 = npt.NDArray[np.float64]
U32 = npt.NDArray[np.uint32]

def check(v: F64, f: U32) -> None: ...
def measures(v: F64, f: U32) -> Tuple[float, float, bool]: ...
def info(v: F64, f: U32) -> str: ...
class Boolean:
    def report(self, v: F64, f: U32) -> str: ...
    def assumed(self) -> List[str]: ...
    def provenance(self) -> Tuple[npt.NDArray[np.uint8], U32, npt.NDArray[np.bool_]]: ...

def boolean(
    av: F64,
    af: U32,
    bv: F64,
    bf: U32,
    op: str,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Optional[int],
    keep_nonmanifold: bool,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    coplanar_refinement: bool = False,
) -> Tuple[F64, U32, Boolean]: ...

class Operand:
    def __init__(
        self,
        v: F64,
        f: U32,
        name: str,
        force: bool,
        self_check: bool,
        resolve: bool,
        orient: bool,
        threads: Optional[int],
    ) -> None: ...
    def report(self) -> str: ...
    def arrays(self) -> Tuple[F64, U32]: ...

def boolean_operands(
    a: Operand,
    b: Operand,
    op: str,
    threads: Optional[int],
    keep_nonmanifold: bool,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    coplanar_refinement: bool = False,
) -> Tuple[F64, U32, Boolean]: ...

def boolean_many(
    meshes: List[Tuple[F64, U32]],
    op: str,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Optional[int],
    keep_nonmanifold: bool,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    one_arrangement: bool = False,
) -> Tuple[F64, U32, U32, U32, str]: ...

class Split:
    def groups(self) -> List[str]: ...
    def group(self, name: str) -> Optional[Tuple[F64, U32]]: ...
    def components(self, name: str) -> List[Tuple[F64, U32]]: ...
    def pick(
        self, specs: List[str], keep_nonmanifold: bool, snap: float = 0.0
    ) -> Tuple[F64, U32, str]: ...
    def report(self, format: str) -> str: ...
    def write(self, dir: str, format: str) -> str: ...

def split(
    av: F64,
    af: U32,
    bv: F64,
    bf: U32,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Optional[int],
    merge_small: int,
    snap: float = 0.0,
    keep_seam_points: bool = False,
    coplanar_refinement: bool = False,
) -> Split: ...
def pieces_for_op(op: str) -> List[str]: ...
def pick(
    pieces: List[Tuple[F64, U32, bool]], keep_nonmanifold: bool, snap: float = 0.0
) -> Tuple[F64, U32, str]: ...
def curves(
    av: F64,
    af: U32,
    b: Optional[Tuple[F64, U32]],
    with_coplanar: bool,
    simplify: Optional[float] = None,
    tagged: bool = False,
    coplanar_refinement: bool = False,
) -> Tuple[List[Tuple[F64, bool]], str]: ...
def cutfill(
    dv: F64, df: U32, tv: F64, tf: U32, threads: Optional[int]
) -> Tuple[str, List[Tuple[F64, bool]]]: ...
def classify(
    v: F64, f: U32, points: F64, force: bool, threads: Optional[int]
) -> Tuple[npt.NDArray[np.uint8], F64, str]: ...
def resolve(
    v: F64,
    f: U32,
    rule: str,
    keep_nonmanifold: bool,
    threads: Optional[int],
    snap: float = 0.0,
) -> Tuple[F64, U32, U32, str]: ...
def envelope(
    v: F64, f: U32, side: str, threads: Optional[int]
) -> Tuple[F64, U32, U32, str]: ...
def orient(v: F64, f: U32, facing: str) -> Tuple[F64, U32, str]: ...
def close(
    v: F64, f: U32, mode: str, floor_offset: float, max_gap: Optional[float]
) -> Tuple[F64, U32, str]: ...
def repair(v: F64, f: U32, config: str) -> Tuple[F64, U32, str]: ...
def terrain(
    center: Tuple[float, float, float],
    size: Tuple[float, float],
    cells: Tuple[int, int],
    relief: float,
    seed: int,
) -> Tuple[F64, U32, str]: ...
def pit(
    center: Tuple[float, float, float],
    radius: Tuple[float, float],
    depth: float,
    benches: int,
    berm: float,
    segments: int,
) -> Tuple[F64, U32, str]: ...
def shape_defaults() -> str: ...
def read(path: str, format: Optional[str] = None) -> Tuple[F64, U32, str]: ...
def write(path: str, v: F64, f: U32, format: Optional[str] = None) -> None: ...

class CsgCache:
    def __init__(self, dir: Optional[str] = None) -> None: ...
    def __len__(self) -> int: ...
    def clear(self) -> None: ...

def csg(
    text: str,
    base: str,
    meshes: List[Tuple[F64, U32]],
    cache: CsgCache,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Optional[int],
    keep_nonmanifold: bool,
    snap: float,
    keep_seam_points: bool,
) -> Tuple[Optional[Tuple[F64, U32]], str]: ...
