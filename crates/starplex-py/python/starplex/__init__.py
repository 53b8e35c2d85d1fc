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
    IaStar,
    IncidenceGraph,
    Is,
    SimplexTree,
    StellarTree,
    Structure,
    __version__,
    read,
)

__all__ = [
    "Complex",
    "Hasse",
    "IaStar",
    "IncidenceGraph",
    "Is",
    "SimplexTree",
    "StellarTree",
    "Structure",
    "read",
    "from_meshio",
    "to_trimesh",
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


def from_meshio(mesh, **options):
    """A Complex from a ``meshio.Mesh`` (meshio is not imported; any object with ``points``
    and ``cells`` blocks of ``type`` and ``data`` works).

    >>> import numpy as np, types, starplex
    >>> block = types.SimpleNamespace(type="triangle", data=np.array([[0, 1, 2]]))
    >>> m = types.SimpleNamespace(points=np.eye(3), cells=[block])
    >>> starplex.from_meshio(m).n_cells
    1
    """
    blocks = []
    for b in mesh.cells:
        kind = _MESHIO.get(b.type)
        if kind is None:
            raise ValueError(f"meshio cell type '{b.type}' has no starplex counterpart")
        blocks.append((kind, b.data))
    return Complex(mesh.points, blocks, **options)


def to_trimesh(c, **options):
    """The triangles of ``c`` as a ``trimesh.Trimesh`` (imports trimesh; ``process=False`` so
    vertex ids are kept)."""
    import trimesh  # noqa: PLC0415 (imported only when asked)

    tris = [a for kind, a in c.cell_blocks if kind == "tri"]
    if len(tris) != len(c.cell_blocks):
        raise ValueError("to_trimesh: the complex has cells other than triangles")
    import numpy as np  # noqa: PLC0415

    faces = np.concatenate(tris) if tris else np.zeros((0, 3), dtype=np.uint32)
    pts = c.points
    if pts.shape[1] != 3:
        raise ValueError(f"to_trimesh: needs 3D points, these have {pts.shape[1]} coordinates")
    options.setdefault("process", False)
    return trimesh.Trimesh(vertices=pts, faces=faces, **options)


def csr_rows(offsets, values):
    """The rows of a CSR answer as a list of arrays (a convenience for small answers).

    >>> import numpy as np, starplex
    >>> [r.tolist() for r in starplex.csr_rows(np.array([0, 2, 3]), np.array([5, 6, 7]))]
    [[5, 6], [7]]
    """
    return [values[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
