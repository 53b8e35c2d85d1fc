#!/usr/bin/env python3
"""Writes the binary-format test corpus of starplex (crates/starplex/tests/data/io/).

Needs meshio and numpy (`python3 -m venv /tmp/iovenv && /tmp/iovenv/bin/pip install meshio numpy`).

- `mixed.json`: the reference mesh (points, cells by meshio type, VTK vertex order: meshio's
  own wedges are in gmsh's order, the mirror image, and are permuted here);
- meshio's writers: gmsh 2.2 and 4.1 binary and ascii, legacy VTK 4.2 and 5.1 binary and ascii;
- hand-written (meshio does not write them): big-endian gmsh 2.2 and 4.1 binary, the 4.1 one
  with non-contiguous node tags, a binary $Entities section, a parametric node block and two
  node blocks.

Usage: scripts/make_io_corpus.py [OUT_DIR]
       scripts/make_io_corpus.py --big N OUT.msh OUT.vtk   (a Kuhn grid of N^3 cubes, for benchmarks)
"""
import json
import os
import struct
import sys

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "starplex", "tests", "data", "io")

# meshio type -> (gmsh type, number of nodes)
GMSH = {"line": (1, 2), "triangle": (2, 3), "quad": (3, 4), "tetra": (4, 4),
        "hexahedron": (5, 8), "wedge": (6, 6), "pyramid": (7, 5)}
# meshio keeps wedges in gmsh's prism order (it permutes them when writing VTK); VTK's wedge is
# the mirror image: VTK node i is gmsh node PRISM[i]
PRISM = [0, 2, 1, 3, 5, 4]


def mixed():
    """Disjoint cells of every kind (no cell is a face of another), deterministic points."""
    rng = np.random.default_rng(11)
    cells = []
    pts = []

    def add(kind, n):
        base = len(pts)
        for _ in range(n):
            pts.append(rng.uniform(-5.0, 5.0, 3).round(6))
        cells.append((kind, [list(range(base, base + n))]))

    for kind, n in [("tetra", 4), ("tetra", 4), ("hexahedron", 8), ("wedge", 6),
                    ("pyramid", 5), ("triangle", 3), ("quad", 4), ("line", 2)]:
        add(kind, n)
    # merge runs of one kind into blocks (meshio writes one block per kind and run)
    blocks = []
    for kind, c in cells:
        if blocks and blocks[-1][0] == kind:
            blocks[-1][1].extend(c)
        else:
            blocks.append((kind, list(c)))
    points = np.array(pts, dtype=np.float64)
    return meshio.Mesh(points, [(k, np.array(c, dtype=np.int64)) for k, c in blocks])


def gmsh41_be(path, mesh):
    """Big-endian gmsh 4.1 binary: non-contiguous node tags in two blocks (the second
    parametric), a binary $Entities section, $PhysicalNames, element tags not from 1."""
    be = ">"
    n = len(mesh.points)
    tags = [10 * i + 7 for i in range(n)]  # non-contiguous
    with open(path, "wb") as f:
        f.write(b"$MeshFormat\n4.1 1 8\n")
        f.write(struct.pack(be + "i", 1))
        f.write(b"\n$EndMeshFormat\n")
        f.write(b'$PhysicalNames\n1\n3 1 "volume"\n$EndPhysicalNames\n')
        f.write(b"$Entities\n")
        f.write(struct.pack(be + "4Q", 1, 0, 0, 1))
        f.write(struct.pack(be + "i3dQ", 1, 0.0, 0.0, 0.0, 0))
        f.write(struct.pack(be + "i6dQiQi", 1, -5, -5, -5, 5, 5, 5, 1, 1, 1, 1))
        f.write(b"\n$EndEntities\n")
        f.write(b"$Nodes\n")
        half = n // 2
        f.write(struct.pack(be + "4Q", 2, n, min(tags), max(tags)))
        # block 1: entity dim 3, not parametric
        f.write(struct.pack(be + "iiiQ", 3, 1, 0, half))
        f.write(struct.pack(be + "%dQ" % half, *tags[:half]))
        for p in mesh.points[:half]:
            f.write(struct.pack(be + "3d", *p))
        # block 2: entity dim 1, parametric (one extra value per node)
        f.write(struct.pack(be + "iiiQ", 1, 1, 1, n - half))
        f.write(struct.pack(be + "%dQ" % (n - half), *tags[half:]))
        for p in mesh.points[half:]:
            f.write(struct.pack(be + "4d", p[0], p[1], p[2], 0.5))
        f.write(b"\n$EndNodes\n")
        ne = sum(len(b.data) for b in mesh.cells)
        f.write(b"$Elements\n")
        f.write(struct.pack(be + "4Q", len(mesh.cells), ne, 101, 100 + ne))
        etag = 101
        for b in mesh.cells:
            gt, k = GMSH[b.type]
            f.write(struct.pack(be + "iiiQ", 3, 1, gt, len(b.data)))
            for c in b.data:
                f.write(struct.pack(be + "Q%dQ" % k, etag, *[tags[v] for v in c]))
                etag += 1
        f.write(b"\n$EndElements\n")
        f.write(b"$NodeData\n1\n\"x\"\n1\n0.0\n3\n0\n1\n0\n$EndNodeData\n")


def gmsh22_be(path, mesh):
    """Big-endian gmsh 2.2 binary, one element header per cell block, 2 tags per element."""
    be = ">"
    n = len(mesh.points)
    with open(path, "wb") as f:
        f.write(b"$MeshFormat\n2.2 1 8\n")
        f.write(struct.pack(be + "i", 1))
        f.write(b"\n$EndMeshFormat\n")
        f.write(b"$Nodes\n%d\n" % n)
        for i, p in enumerate(mesh.points):
            f.write(struct.pack(be + "i3d", i + 1, *p))
        f.write(b"\n$EndNodes\n")
        ne = sum(len(b.data) for b in mesh.cells)
        f.write(b"$Elements\n%d\n" % ne)
        etag = 1
        for b in mesh.cells:
            gt, k = GMSH[b.type]
            f.write(struct.pack(be + "3i", gt, len(b.data), 2))
            for c in b.data:
                f.write(struct.pack(be + "3i%di" % k, etag, 0, 1, *[v + 1 for v in c]))
                etag += 1
        f.write(b"\n$EndElements\n")


def corpus(out):
    os.makedirs(out, exist_ok=True)
    m = mixed()
    vtk_order = lambda b: b.data[:, PRISM] if b.type == "wedge" else b.data
    ref = {"points": m.points.tolist(),
           "cells": [[b.type, vtk_order(b).tolist()] for b in m.cells]}
    with open(os.path.join(out, "mixed.json"), "w") as f:
        json.dump(ref, f)
    m.cell_data = {"gmsh:physical": [np.full(len(b.data), 1) for b in m.cells],
                   "gmsh:geometrical": [np.full(len(b.data), i + 1) for i, b in enumerate(m.cells)]}
    dim = {"line": 1, "triangle": 2, "quad": 2}
    dim_tags = np.zeros((len(m.points), 2), dtype=np.int64)
    for i, b in enumerate(m.cells):
        for c in b.data:
            dim_tags[c] = [dim.get(b.type, 3), i + 1]
    m.point_data = {"gmsh:dim_tags": dim_tags}
    for ver in ["2.2", "4.1"]:
        for binary in [True, False]:
            name = "mixed_%s_%s.msh" % (ver.replace(".", ""), "bin" if binary else "ascii")
            meshio.gmsh.write(os.path.join(out, name), m, fmt_version=ver, binary=binary)
    m.cell_data = {}
    m.point_data = {"height": m.points[:, 2].copy()}
    from meshio.vtk import _vtk_42, _vtk_51
    for mod, ver in [(_vtk_42, "42"), (_vtk_51, "51")]:
        for binary in [True, False]:
            name = "mixed_%s_%s.vtk" % (ver, "bin" if binary else "ascii")
            mod.write(os.path.join(out, name), m, binary=binary)
    gmsh41_be(os.path.join(out, "mixed_41_be.msh"), m)
    gmsh22_be(os.path.join(out, "mixed_22_be.msh"), m)


def kuhn_grid(n):
    """The Freudenthal triangulation of an n^3 grid (what `starplex generate grid n n n` makes,
    up to the order of the tetrahedra)."""
    g = np.arange(n + 1)
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    pts = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1).astype(np.float64)
    vid = lambda i, j, k: (i * (n + 1) + j) * (n + 1) + k
    c = np.stack(np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij"), -1).reshape(-1, 3)
    tets = []
    import itertools
    for perm in itertools.permutations(range(3)):
        cur = c.copy()
        verts = [vid(cur[:, 0], cur[:, 1], cur[:, 2])]
        for a in perm:
            cur = cur.copy()
            cur[:, a] += 1
            verts.append(vid(cur[:, 0], cur[:, 1], cur[:, 2]))
        tets.append(np.stack(verts, axis=1))
    return meshio.Mesh(pts, [("tetra", np.concatenate(tets).astype(np.int64))])


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--big":
        n = int(sys.argv[2])
        m = kuhn_grid(n)
        meshio.gmsh.write(sys.argv[3], m, fmt_version="4.1", binary=True)
        from meshio.vtk import _vtk_42
        _vtk_42.write(sys.argv[4], m, binary=True)
    else:
        corpus(sys.argv[1] if len(sys.argv) > 1 else OUT)
