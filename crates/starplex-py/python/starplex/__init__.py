"""starplex: topology of meshes and simplicial complexes, NumPy in and NumPy out.

Build a complex from arrays (or read a file), build a data structure on it, and ask any
relation of one id, an array of ids or every item at once; ragged answers come back as CSR
pairs ``(offsets, values)``: the answer of item ``i`` is ``values[offsets[i]:offsets[i + 1]]``.

>>> import numpy as np, starplex
>>> pts = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=float)
>>> c = starplex.Complex(pts, np.array([[0, 1, 2], [1, 3, 2]]))
>>> t = starplex.IaStar(c)
>>> t.vt(1).tolist()
[0, 1]
>>> offsets, values = t.vt()          # every vertex at once
>>> offsets.tolist(), values.tolist()
([0, 1, 3, 5, 6], [0, 0, 1, 0, 1, 1])
>>> c.info()["euler_characteristic"]
1

Every call releases the GIL while it works. Errors are ``ValueError`` (bad values, bad
files), ``TypeError`` (wrong dtypes) and ``OSError`` (files that cannot be opened or written),
carrying the messages of the ``starplex`` command line.
"""
from ._starplex import (  # noqa: F401
    Complex,
    Hasse,
    HasseComplex,
    IaStar,
    IncidenceGraph,
    Is,
    SimplexTree,
    StellarTree,
    Structure,
    __version__,
    flag,
    read,
    rips,
)

__all__ = [
    "Complex",
    "Hasse",
    "HasseComplex",
    "IaStar",
    "IncidenceGraph",
    "Is",
    "SimplexTree",
    "StellarTree",
    "Structure",
    "read",
    "rips",
    "flag",
    "from_meshio",
    "to_trimesh",
    "to_meshio",
    "to_pyvista",
    "csr_rows",
]

# meshio cell type names -> starplex's
_MESHIO = {
    "vertex": "vertex",
    "line": "line",
    "triangle": "tri",
    "quad": "quad",
    "tetra": "tet",
    "pyramid": "pyramid",
    "wedge": "prism",
    "hexahedron": "hex",
}


def _column(a):
    """One attribute column for a library that takes scalars as ``(n,)`` arrays."""
    return a[:, 0] if a.ndim == 2 and a.shape[1] == 1 else a


def from_meshio(mesh, **options):
    """A Complex from a ``meshio.Mesh`` (meshio is not imported; any object with ``points``
    and ``cells`` blocks of ``type`` and ``data`` works). ``mesh.point_data`` and
    ``mesh.cell_data`` (one array per cell block) become ``point_data`` / ``cell_data``.

    >>> import numpy as np, types, starplex
    >>> block = types.SimpleNamespace(type="triangle", data=np.array([[0, 1, 2]]))
    >>> m = types.SimpleNamespace(points=np.eye(3), cells=[block], cell_data={"tag": [[4]]})
    >>> c = starplex.from_meshio(m)
    >>> c.n_cells, c.cell_data["tag"].tolist()
    (1, [[4]])
    """
    import numpy as np  # noqa: PLC0415

    blocks = []
    for b in mesh.cells:
        kind = _MESHIO.get(b.type)
        if kind is None:
            raise ValueError(f"meshio cell type '{b.type}' has no starplex counterpart")
        blocks.append((kind, b.data))
    point_data = dict(getattr(mesh, "point_data", None) or {})
    cell_data = {}
    for name, per_block in (getattr(mesh, "cell_data", None) or {}).items():
        if len(per_block) != len(blocks):
            raise ValueError(
                f"cell_data['{name}']: {len(per_block)} arrays for {len(blocks)} cell blocks"
            )
        cell_data[name] = np.concatenate([np.asarray(a) for a in per_block]) if blocks else []
    options.setdefault("point_data", point_data or None)
    options.setdefault("cell_data", cell_data or None)
    return Complex(mesh.points, blocks, **options)


# starplex cell kinds -> meshio's and VTK's (VTK's vertex order is starplex's)
_TO_MESHIO = {v: k for k, v in _MESHIO.items()}
_VTK_TYPE = {
    "vertex": 1,
    "line": 3,
    "tri": 5,
    "quad": 9,
    "tet": 10,
    "hex": 12,
    "prism": 13,
    "pyramid": 14,
}


def _kind_map(c, table, what):
    for kind, _ in c.cell_blocks:
        if kind not in table:
            raise ValueError(f"{what}: cells of kind '{kind}' have no counterpart there")


def to_meshio(c):
    """``c`` as a ``meshio.Mesh`` (imports meshio), with its ``point_data`` and ``cell_data``
    (split per cell block, one-component columns as ``(n,)`` arrays)."""
    import meshio  # noqa: PLC0415 (imported only when asked)
    import numpy as np  # noqa: PLC0415

    _kind_map(c, _TO_MESHIO, "to_meshio")
    blocks = c.cell_blocks
    cells = [(_TO_MESHIO[kind], np.array(a)) for kind, a in blocks]  # writeable copies
    ends, n = [], 0
    for _, a in blocks:
        n += len(a)
        ends.append(n)
    cell_data = {}
    for name, a in c.cell_data.items():
        a = _column(a)
        cell_data[name] = [a[e - len(b):e] for e, (_, b) in zip(ends, blocks)]
    point_data = {name: _column(a) for name, a in c.point_data.items()}
    return meshio.Mesh(np.array(c.points), cells, point_data=point_data, cell_data=cell_data)


def to_pyvista(c):
    """``c`` as a ``pyvista.UnstructuredGrid`` (imports pyvista), cells in id order, with its
    ``point_data`` and ``cell_data``; points of 1 or 2 coordinates get zeros up to 3."""
    try:
        import pyvista  # noqa: PLC0415 (imported only when asked)
    except ImportError as e:
        raise ImportError(
            "to_pyvista needs pyvista (pip install pyvista); without it, use "
            "starplex.to_meshio(c) or c.write('mesh.vtu')"
        ) from e
    import numpy as np  # noqa: PLC0415

    _kind_map(c, _VTK_TYPE, "to_pyvista")
    pts = np.array(c.points)  # a writeable copy: the grid owns its points
    if pts.shape[1] > 3:
        raise ValueError(f"to_pyvista: needs at most 3 coordinates, these have {pts.shape[1]}")
    if pts.shape[1] < 3:
        pts = np.hstack([pts, np.zeros((len(pts), 3 - pts.shape[1]))])
    parts, types = [], []
    for kind, a in c.cell_blocks:
        m, k = a.shape
        parts.append(np.hstack([np.full((m, 1), k, dtype=np.int64), a.astype(np.int64)]).ravel())
        types.append(np.full(m, _VTK_TYPE[kind], dtype=np.uint8))
    cells = np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)
    celltypes = np.concatenate(types) if types else np.zeros(0, dtype=np.uint8)
    grid = pyvista.UnstructuredGrid(cells, celltypes, pts)
    for name, a in c.point_data.items():
        grid.point_data[name] = _column(a)
    for name, a in c.cell_data.items():
        grid.cell_data[name] = _column(a)
    return grid


def to_trimesh(c, **options):
    """The triangles of ``c`` as a ``trimesh.Trimesh`` (imports trimesh; ``process=False`` so
    vertex ids are kept); ``point_data`` / ``cell_data`` become ``vertex_attributes`` /
    ``face_attributes``."""
    import trimesh  # noqa: PLC0415 (imported only when asked)

    tris = [a for kind, a in c.cell_blocks if kind == "tri"]
    if len(tris) != len(c.cell_blocks):
        raise ValueError("to_trimesh: the complex has cells other than triangles")
    import numpy as np  # noqa: PLC0415

    faces = np.concatenate(tris) if tris else np.zeros((0, 3), dtype=np.uint32)
    pts = np.array(c.points)  # a writeable copy: the mesh owns its vertices
    if pts.shape[1] != 3:
        raise ValueError(f"to_trimesh: needs 3D points, these have {pts.shape[1]} coordinates")
    options.setdefault("process", False)
    options.setdefault("vertex_attributes", {n: _column(a) for n, a in c.point_data.items()})
    options.setdefault("face_attributes", {n: _column(a) for n, a in c.cell_data.items()})
    return trimesh.Trimesh(vertices=pts, faces=faces, **options)


def csr_rows(offsets, values):
    """The rows of a CSR answer as a list of arrays (a convenience for small answers).

    >>> import numpy as np, starplex
    >>> [r.tolist() for r in starplex.csr_rows(np.array([0, 2, 3]), np.array([5, 6, 7]))]
    [[5, 6], [7]]
    """
    return [values[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
