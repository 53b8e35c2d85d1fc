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
AttrArray = Union[npt.NDArray[np.int64], npt.NDArray[np.float64]]
"""An attribute column: (n, components), int64 or float64."""
DataArg = Optional[Mapping[str, npt.ArrayLike]]
"""name -> (n,) or (n, components) array of ints or floats."""
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
        point_data: DataArg = None,
        cell_data: DataArg = None,
    ) -> None:
        """`point_data` / `cell_data`: one row per vertex / per given cell (cells dropped by
        `drop_faces` / `drop_duplicates` take their rows along); wrong lengths raise ValueError
        naming the attribute.

        Arrays are copied, except a C-contiguous float64 `points` / uint32 cell array whose
        memory nobody can write: a read-only memory map (`np.load(f, mmap_mode="r")`), an array
        over `bytes`, or another complex's `points` / `cells`. Those are shared (checked, never
        copied) and kept alive by the complex."""
    @property
    def n_vertices(self) -> int: ...
    @property
    def n_cells(self) -> int: ...
    @property
    def point_data(self) -> Dict[str, AttrArray]:
        """Vertex attributes, name -> (n_vertices, components) array (a new dict of copies:
        assign a whole dict to change them).

        >>> c.point_data = {"height": c.points[:, 2]}
        """
    @point_data.setter
    def point_data(self, value: DataArg) -> None: ...
    @property
    def cell_data(self) -> Dict[str, AttrArray]:
        """Cell attributes, name -> (n_cells, components) array, in cell id order."""
    @cell_data.setter
    def cell_data(self, value: DataArg) -> None: ...
    @property
    def ambient_dim(self) -> int: ...
    @property
    def dim(self) -> Optional[int]: ...
    @property
    def points(self) -> npt.NDArray[np.float64]:
        """(n, d) float64 coordinates: a read-only view of the complex's memory, no copy
        (`np.array(c.points)` for a writeable copy)."""
    @property
    def cells(self) -> Union[IdArray, List[IdArray]]:
        """One (m, k) uint32 array for one kind of cell, else one array per block (read-only
        views, as `points`)."""
    @property
    def cell_blocks(self) -> List[Tuple[str, IdArray]]:
        """[(kind, (m, k) uint32 array)] in cell-id order (read-only views, as `points`)."""
    def vt(self) -> CSR:
        """VT of every vertex straight from the complex (no structure built)."""
    def write(self, path: Path, format: Optional[str] = None) -> None:
        """Writes atomically; lossy writes (tetrahedra to OFF, ...) raise ValueError.
        Attributes are written by VTK (all) and Medit (medit:ref); a UserWarning names those
        a format drops."""
    def simplify(
        self,
        *,
        mode: Optional[str] = None,
        ratio: Optional[float] = None,
        faces: Optional[int] = None,
        vertices: Optional[int] = None,
        max_error: Optional[float] = None,
        keep_manifold: bool = False,
        lock_boundary: bool = False,
        report: bool = True,
    ) -> Tuple[Complex, Dict[str, Any]]:
        """Edge contraction that keeps the topology (`starplex simplify`): mode "qem" (triangle
        and tetrahedral meshes, their default) or "homology" (any simplicial complex); stops at
        the first target reached. Returns the new complex and the report of
        `simplify --json` (before/after f-vector, Betti numbers, topology_kept, ...).

        >>> small, r = c.simplify(mode="homology", ratio=0.1)
        >>> r["topology_kept"]
        True
        """
    @overload
    def render(
        self,
        path: None = None,
        *,
        size: Union[Tuple[int, int], str, None] = None,
        color: Union[str, Tuple[str, str], None] = None,
        view: Optional[str] = None,
        up: str = "z",
        edges: bool = False,
        clip: Optional[str] = None,
        shading: bool = True,
        legend: bool = True,
        title: Optional[str] = None,
        kv: Optional[int] = None,
    ) -> bytes: ...
    @overload
    def render(
        self,
        path: Path,
        *,
        size: Union[Tuple[int, int], str, None] = None,
        color: Union[str, Tuple[str, str], None] = None,
        view: Optional[str] = None,
        up: str = "z",
        edges: bool = False,
        clip: Optional[str] = None,
        shading: bool = True,
        legend: bool = True,
        title: Optional[str] = None,
        kv: Optional[int] = None,
    ) -> None:
        """A picture (`starplex render`): PNG bytes (path None), or writes a .png / .svg.
        size (w, h) or "WxH" (default 1024x768); color plain, blocks, components, defects,
        boundary, ("label", CELL_ATTR) or ("field", VERTEX_ATTR); view iso, front, top, side
        or "AZ,EL".

        >>> png = c.render(size=(640, 480), color="components")
        >>> c.render("mesh.png", view="top", edges=True)
        """
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

class HasseComplex:
    """The editable CASC Hasse complex with per-level data as NumPy columns (levels 0-11).
    Simplices are named by vertex labels; ids are slots (stable under edits of others, freed
    slots reused). Merges keep the first row (positions: the mean); new simplices have no row
    (NaN / 0, has_data False).

    >>> h = starplex.HasseComplex(c)          # c.point_data -> level 0, c.cell_data -> top
    >>> ids, edges = h.simplices(1)
    >>> h.set_data(1, "length", lengths)      # aligned with simplices(1)
    >>> h.collapse([3, 7]); h.flip([2, 5]); h.split([0, 1]); h.decimate([4, 5, 6])
    >>> h.smooth(0.5, 3); k = h.to_complex()
    """

    def __init__(self, c: Complex) -> None: ...
    def f_vector(self) -> List[int]: ...
    def simplices(self, p: int) -> Tuple[IdArray, IdArray]:
        """(ids, (n_p, p + 1) vertex labels) of the live p-simplices, in id order."""
    def data(self, p: int) -> Dict[str, AttrArray]:
        """Level p's columns aligned with simplices(p)."""
    def has_data(self, p: int) -> npt.NDArray[np.bool_]: ...
    def set_data(self, p: int, name: str, values: npt.ArrayLike) -> None:
        """One row per p-simplex in simplices(p) order; replaces a column of that name."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """(n_0, 3) vertex positions in simplices(0) order."""
    @positions.setter
    def positions(self, value: npt.ArrayLike) -> None: ...
    def collapse(self, edge: Ids) -> int:
        """Link-checked edge collapse; returns the label kept (at the midpoint)."""
    def flip(self, simplex: Ids) -> List[int]:
        """Bistellar flip; returns the new simplex's labels."""
    def split(self, simplex: Ids) -> int:
        """Stellar split at a new vertex (at the centroid); returns its label."""
    def decimate(self, simplex: Ids) -> int:
        """CASC generalized decimation into a new vertex (at the mean); returns its label."""
    def smooth(self, lam: float = 0.5, iterations: int = 1, fix_boundary: bool = True) -> None: ...
    def to_complex(self, *, labels: bool = False) -> Complex:
        """The maximal simplices, vertices renumbered in label order, level 0 as point_data."""

def rips(
    points: npt.ArrayLike,
    eps: Optional[float] = None,
    *,
    eps_nn: Optional[float] = None,
    max_dim: Optional[int] = None,
    max_memory: Optional[float] = None,
) -> Complex:
    """Vietoris-Rips complex of an (n, d) point cloud at scale eps (or eps_nn times the
    median nearest-neighbour distance), by its maximal simplices; max_dim keeps the
    K-skeleton; max_memory in GiB.

    >>> c = starplex.rips(pts, 0.3, max_dim=2)
    >>> starplex.SimplexTree(c).f_vector()
    """

def flag(
    edges: npt.ArrayLike,
    n_vertices: Optional[int] = None,
    *,
    max_dim: Optional[int] = None,
    max_memory: Optional[float] = None,
) -> Complex:
    """Flag (clique) complex of an (m, 2) edge list; vertices have one coordinate, their id."""

def from_meshio(mesh: Any, **options: Any) -> Complex:
    """A Complex from a meshio.Mesh (meshio itself is not imported), with its point_data and
    cell_data."""

def to_meshio(c: Complex) -> Any:
    """A meshio.Mesh with point_data and cell_data (imports meshio when called)."""

def to_pyvista(c: Complex) -> Any:
    """A pyvista.UnstructuredGrid with point_data and cell_data (imports pyvista when
    called; ImportError with a hint when it is missing)."""

def to_trimesh(c: Complex, **options: Any) -> Any:
    """A trimesh.Trimesh of a triangle complex (imports trimesh when called), attributes as
    vertex_attributes / face_attributes."""

def csr_rows(offsets: Offsets, values: npt.NDArray[Any]) -> List[npt.NDArray[Any]]: ...
