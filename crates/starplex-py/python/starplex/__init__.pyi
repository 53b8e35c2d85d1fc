"""Type stubs of starplex (the native module re-exported by the package)."""
from os import PathLike
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

Path = Union[str, PathLike]
IdArray = npt.NDArray[np.uint32]
Offsets = npt.NDArray[np.int64]
CSR = Tuple[Offsets, IdArray]
"""(offsets, values): the answer of item i is values[offsets[i]:offsets[i + 1]]."""
Ids = Union[int, Sequence[int], npt.ArrayLike]
CellsArg = Union[
    npt.ArrayLike,
    Sequence[npt.ArrayLike],
    Sequence[Tuple[str, npt.ArrayLike]],
    Mapping[str, npt.ArrayLike],
]

def read(
    path: Path,
    *,
    format: Optional[str] = None,
    simplices: bool = False,
    drop_faces: bool = False,
    drop_duplicates: bool = False,
) -> Complex:
    """Reads a complex (format from `format`, the extension or the content).

    >>> c = starplex.read("mesh.off")
    Raises ValueError (bad content, naming file and line) or OSError (cannot open).
    """

class Complex:
    """Vertices with coordinates and top cells; cell ids are input positions.

    >>> c = starplex.Complex(np.eye(3), [[0, 1, 2]])
    >>> c = starplex.Complex(pts, {"quad": quads, "tri": tris})
    """

    def __init__(
        self,
        points: npt.ArrayLike,
        cells: CellsArg,
        *,
        drop_faces: bool = False,
        drop_duplicates: bool = False,
    ) -> None: ...
    @property
    def n_vertices(self) -> int: ...
    @property
    def n_cells(self) -> int: ...
    @property
    def ambient_dim(self) -> int: ...
    @property
    def dim(self) -> Optional[int]: ...
    @property
    def points(self) -> npt.NDArray[np.float64]:
        """(n, d) float64 coordinates (a copy)."""
    @property
    def cells(self) -> Union[IdArray, List[IdArray]]:
        """One (m, k) uint32 array for one kind of cell, else one array per block."""
    @property
    def cell_blocks(self) -> List[Tuple[str, IdArray]]:
        """[(kind, (m, k) uint32 array)] in cell-id order."""
    def vt(self) -> CSR:
        """VT of every vertex straight from the complex (no structure built)."""
    def write(self, path: Path, format: Optional[str] = None) -> None:
        """Writes atomically; lossy writes (tetrahedra to OFF, ...) raise ValueError."""
    def info(self, *, max_faces: Optional[int] = None, betti: bool = False) -> Dict[str, Any]:
        """The keys of `starplex info --json` (n_vertices, f_vector, euler_characteristic, ...).

        >>> c.info()["f_vector"]
        [3, 3, 1]
        """
    def validate(self, *, kv: Optional[int] = None) -> Dict[str, Any]:
        """`starplex validate --json` with complete id arrays (non_manifold_vertices,
        non_manifold_edges (n, 2), boundary_faces (n, d), cells_to_flip, ...)."""
    def homology(self, field: str = "2", *, per_component: bool = False) -> Dict[str, Any]:
        """Betti numbers over Z/2 ("2"), Z/p ("p" a prime), Q ("q") or Z ("z", with torsion).

        >>> torus.homology()["betti"]
        [1, 2, 1]
        """

class Structure:
    """The queries every structure answers. `ids`: an int (one answer), a 1-D array of ids or
    None (every item) for a CSR pair. Simplices are (n, p + 1) uint32 arrays."""

    @property
    def n_vertices(self) -> int: ...
    @property
    def n_top_cells(self) -> int: ...
    @property
    def storage_bytes(self) -> int: ...
    @overload
    def vt(self, ids: int) -> IdArray: ...
    @overload
    def vt(self, ids: Optional[Ids] = None) -> CSR:
        """Top cells incident to each vertex.

        >>> s.vt(2)            # array([0, 1], dtype=uint32)
        >>> off, val = s.vt()  # every vertex
        """
    @overload
    def vv(self, ids: int) -> IdArray: ...
    @overload
    def vv(self, ids: Optional[Ids] = None) -> CSR: ...
    @overload
    def tv(self, ids: int) -> IdArray: ...
    @overload
    def tv(self, ids: Optional[Ids] = None) -> CSR: ...
    @overload
    def tt(self, ids: int) -> IdArray: ...
    @overload
    def tt(self, ids: Optional[Ids] = None) -> CSR: ...
    @overload
    def link(self, ids: int) -> List[IdArray]: ...
    @overload
    def link(self, ids: Optional[Ids] = None) -> List[CSR]:
        """Per level p: the link's p-simplices ((n_p, p + 1) arrays, or CSR per vertex)."""
    @overload
    def star(self, ids: int) -> List[IdArray]: ...
    @overload
    def star(self, ids: Optional[Ids] = None) -> List[CSR]: ...
    @overload
    def boundary(self, simplices: int, q: int = 0) -> IdArray: ...
    @overload
    def boundary(self, simplices: Optional[npt.ArrayLike] = None, q: int = 0) -> CSR:
        """q-faces of each simplex ((m, k) array; None: every top cell).

        >>> off, edges = s.boundary(q=1)
        """
    @overload
    def coboundary(self, simplices: int, q: int = 1) -> IdArray: ...
    @overload
    def coboundary(self, simplices: Optional[npt.ArrayLike] = None, q: int = 1) -> CSR: ...
    @overload
    def adjacency(self, simplices: int) -> IdArray: ...
    @overload
    def adjacency(self, simplices: Optional[npt.ArrayLike] = None) -> CSR: ...
    def faces(self, p: int) -> IdArray:
        """Every p-simplex, (n_p, p + 1)."""
    def f_vector(self) -> List[int]: ...

class StellarTree(Structure):
    def __init__(self, c: Complex, kv: Optional[int] = None) -> None: ...

class IaStar(Structure):
    def __init__(self, c: Complex) -> None: ...

class SimplexTree(Structure):
    def __init__(self, c: Complex) -> None: ...

class IncidenceGraph(Structure):
    def __init__(self, c: Complex) -> None: ...

class Is(Structure):
    def __init__(self, c: Complex) -> None: ...

class Hasse(Structure):
    def __init__(self, c: Complex) -> None: ...

def from_meshio(mesh: Any, **options: Any) -> Complex:
    """A Complex from a meshio.Mesh (meshio itself is not imported)."""

def to_trimesh(c: Complex, **options: Any) -> Any:
    """A trimesh.Trimesh of a triangle complex (imports trimesh when called)."""

def csr_rows(offsets: Offsets, values: npt.NDArray[Any]) -> List[npt.NDArray[Any]]: ...
