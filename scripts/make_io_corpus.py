#!/usr/bin/env python3
"""Writes the binary-format test corpus of starplex (crates/starplex/tests/data/io/).

Needs meshio and numpy (`python3 -m venv /tmp/iovenv && /tmp/iovenv/bin/pip install meshio numpy`);
with `vtk` installed too it also writes the `vtk_*.vtu` / `vtk_surface.vtp` files by VTK's own writer.

- `mixed.json`: the reference mesh (points, cells by meshio type, VTK vertex order: meshio's
  own wedges are in gmsh's order, the mirror image, and are permuted here);
- meshio's writers: gmsh 2.2 and 4.1 binary and ascii, legacy VTK 4.2 and 5.1 binary and ascii;
- hand-written (meshio does not write them): big-endian gmsh 2.2 and 4.1 binary, the 4.1 one
  with non-contiguous node tags, a binary $Entities section, a parametric node block and two
  node blocks.

Usage: scripts/make_io_corpus.py [OUT_DIR]
       scripts/make_io_corpus.py --big N OUT.msh OUT.vtk [OUT.vtu]   (a Kuhn grid of N^3 cubes, for
       benchmarks; the .vtu with raw appended data)
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
    # VTK XML by meshio: ascii, inline base64 uncompressed and zlib (UInt32 and UInt64 headers)
    meshio.vtu.write(os.path.join(out, "mixed_ascii.vtu"), m, binary=False)
    meshio.vtu.write(os.path.join(out, "mixed_b64.vtu"), m, binary=True, compression=None)
    meshio.vtu.write(os.path.join(out, "mixed_b64_zlib.vtu"), m, binary=True, compression="zlib")
    meshio.vtu.write(os.path.join(out, "mixed_b64_zlib64.vtu"), m, binary=True, compression="zlib",
                     header_type="UInt64")
    # VTK XML with appended data, as VTK/ParaView write it (meshio does not): raw and base64,
    # plain and zlib, little- and big-endian
    for enc, zlib, be, hdr in [("raw", False, False, "UInt32"), ("raw", True, False, "UInt64"),
                               ("raw", False, True, "UInt64"), ("base64", True, True, "UInt32"),
                               ("base64", False, False, "UInt64")]:
        name = "mixed_app_%s%s%s.vtu" % (enc, "_zlib" if zlib else "", "_be" if be else "")
        vtu_appended(os.path.join(out, name), m, enc, zlib, be, hdr)
    vtp_surface(os.path.join(out, "surface.vtp"))
    try:
        import vtk  # noqa: F401  (a large wheel: only where it is installed)
    except ImportError:
        print("vtk is not installed: the VTK-written files are not regenerated")
    else:
        vtk_written(out)


def attributes(out):
    """The mixed mesh with point and cell data of every kind (int and float scalars, float
    vectors), written by meshio as .vtu (ascii, base64 zlib) and legacy .vtk (4.2 and 5.1, ascii
    and binary); `mixed_attrs.json` holds the expected columns (cells in file order)."""
    m = mixed()
    n_cells = sum(len(b.data) for b in m.cells)
    cell_ids = np.arange(n_cells)
    split = np.cumsum([len(b.data) for b in m.cells])[:-1]
    m.point_data = {"height": m.points[:, 2].copy(),
                    "label": (np.arange(len(m.points)) % 5).astype(np.int32),
                    "velocity": np.stack([m.points[:, 1], -m.points[:, 0],
                                          np.zeros(len(m.points))], axis=1)}
    m.cell_data = {"material": [x.astype(np.int32) for x in np.split(cell_ids * 10 + 1, split)],
                   "quality": [x / 8.0 for x in np.split(cell_ids.astype(float), split)]}
    ref = {"vertex": {k: np.asarray(v).reshape(len(m.points), -1).tolist()
                      for k, v in m.point_data.items()},
           "cell": {k: np.concatenate(v).reshape(n_cells, -1).tolist()
                    for k, v in m.cell_data.items()}}
    with open(os.path.join(out, "mixed_attrs.json"), "w") as f:
        json.dump(ref, f)
    meshio.vtu.write(os.path.join(out, "attrs_ascii.vtu"), m, binary=False)
    meshio.vtu.write(os.path.join(out, "attrs_b64_zlib.vtu"), m, binary=True, compression="zlib")
    from meshio.vtk import _vtk_42, _vtk_51
    for mod, ver in [(_vtk_42, "42"), (_vtk_51, "51")]:
        for binary in [True, False]:
            name = "attrs_%s_%s.vtk" % (ver, "bin" if binary else "ascii")
            mod.write(os.path.join(out, name), m, binary=binary)


def vtk_written(out):
    """The same mesh written by VTK itself (its default: appended raw zlib; inline binary; ascii;
    lz4 is left out) and the poly data surface re-written by VTK."""
    import vtk
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(out, "mixed_b64_zlib.vtu"))
    r.Update()
    for name, mode, comp in [("vtk_appended_zlib.vtu", "appended", True),
                             ("vtk_appended_raw.vtu", "appended", False),
                             ("vtk_binary.vtu", "binary", True),
                             ("vtk_ascii.vtu", "ascii", False)]:
        w = vtk.vtkXMLUnstructuredGridWriter()
        w.SetInputData(r.GetOutput())
        w.SetFileName(os.path.join(out, name))
        {"appended": w.SetDataModeToAppended, "binary": w.SetDataModeToBinary,
         "ascii": w.SetDataModeToAscii}[mode]()
        if comp:
            w.SetCompressorTypeToZLib()
        else:
            w.SetCompressorTypeToNone()
        w.Write()
    p = vtk.vtkXMLPolyDataReader()
    p.SetFileName(os.path.join(out, "surface.vtp"))
    p.Update()
    w = vtk.vtkXMLPolyDataWriter()
    w.SetInputData(p.GetOutput())
    w.SetFileName(os.path.join(out, "vtk_surface.vtp"))
    w.Write()


VTK_TYPE = {"line": 3, "triangle": 5, "quad": 9, "tetra": 10, "hexahedron": 12, "wedge": 13,
            "pyramid": 14}


def vtk_array(values, dtype, zlib, be, hdr):
    """The bytes of one array in VTK's binary layout: header (size, or block table) and data."""
    e = ">" if be else "<"
    data = np.asarray(values, dtype=np.dtype(dtype).newbyteorder(e)).tobytes()
    h = e + ("I" if hdr == "UInt32" else "Q")
    if not zlib:
        return struct.pack(h, len(data)), data
    import zlib as z
    block = 256  # small blocks, so the test files have several
    chunks = [data[i:i + block] for i in range(0, len(data), block)] or [b""]
    comp = [z.compress(c) for c in chunks]
    last = len(chunks[-1]) if len(chunks[-1]) != block else 0
    head = struct.pack(e + ("%d" % (3 + len(comp))) + h[1], len(comp), block, last,
                       *[len(c) for c in comp])
    return head, b"".join(comp)


def vtu_appended(path, mesh, enc, zlib, be, hdr):
    """A .vtu with appended data (raw or base64; header and data base64-encoded apart, like VTK)."""
    import base64
    vtk_order = lambda b: b.data[:, PRISM] if b.type == "wedge" else b.data
    conn = np.concatenate([vtk_order(b).ravel() for b in mesh.cells])
    sizes = np.concatenate([np.full(len(b.data), b.data.shape[1]) for b in mesh.cells])
    types = np.concatenate([np.full(len(b.data), VTK_TYPE[b.type]) for b in mesh.cells])
    arrays = [("Points", "", "Float64", 3, mesh.points.ravel()),
              ("Cells", "connectivity", "Int64", 1, conn),
              ("Cells", "offsets", "Int32", 1, np.cumsum(sizes)),
              ("Cells", "types", "UInt8", 1, types),
              ("PointData", "height", "Float32", 1, mesh.points[:, 2])]
    blobs, offsets, at = [], [], 0
    for sec, name, ty, nc, vals in arrays:
        head, data = vtk_array(vals, {"Float64": "f8", "Float32": "f4", "Int64": "i8",
                                      "Int32": "i4", "UInt8": "u1"}[ty], zlib, be, hdr)
        blob = head + data if enc == "raw" else base64.b64encode(head) + base64.b64encode(data)
        offsets.append(at)
        blobs.append(blob)
        at += len(blob)
    da = lambda i: '<DataArray type="%s" Name="%s" NumberOfComponents="%d" format="appended" offset="%d"/>' % (
        arrays[i][2], arrays[i][1], arrays[i][3], offsets[i])
    comp = ' compressor="vtkZLibDataCompressor"' if zlib else ""
    xml = ('<?xml version="1.0"?>\n<!-- written by make_io_corpus.py -->\n'
           '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="%s" header_type="%s"%s>\n'
           '<UnstructuredGrid>\n<Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
           '<PointData Scalars="height">%s</PointData>\n'
           '<Points>%s</Points>\n<Cells>%s%s%s</Cells>\n</Piece>\n</UnstructuredGrid>\n'
           '<AppendedData encoding="%s">\n_' % (
               "BigEndian" if be else "LittleEndian", hdr, comp, len(mesh.points), len(types),
               da(4), da(0), da(1), da(2), da(3), enc))
    with open(path, "wb") as f:
        f.write(xml.encode())
        f.write(b"".join(blobs))
        f.write(b"\n</AppendedData>\n</VTKFile>\n")


def vtp_surface(path):
    """Poly data with every section: a vertex, a poly-line, a strip, a triangle; then a pentagon
    and a quad in a second piece (its point ids start at 0; VTK 9's reader does not shift the ids
    of a section that an earlier piece has no cells in, so the first piece has a polygon too)."""
    piece = lambda pts, verts, lines, strips, polys: (
        '<Piece NumberOfPoints="%d" NumberOfVerts="%d" NumberOfLines="%d" NumberOfStrips="%d" '
        'NumberOfPolys="%d">\n<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">'
        '%s</DataArray></Points>\n' % (len(pts), len(verts), len(lines), len(strips), len(polys),
                                       " ".join("%g %g %g" % tuple(p) for p in pts))
        + "".join(
            '<%s><DataArray type="Int32" Name="connectivity" format="ascii">%s</DataArray>'
            '<DataArray type="Int32" Name="offsets" format="ascii">%s</DataArray></%s>\n' % (
                sec, " ".join(str(v) for c in cells for v in c),
                " ".join(str(o) for o in np.cumsum([len(c) for c in cells])), sec)
            for sec, cells in [("Verts", verts), ("Lines", lines), ("Strips", strips),
                               ("Polys", polys)])
        + "</Piece>\n")
    grid = [(x, y, 0) for y in range(3) for x in range(4)]
    p1 = piece(grid, [[11]], [[0, 1, 2, 3]], [[4, 8, 5, 9, 6, 10]], [[7, 11, 10]])
    penta = [(0, 0, 1), (1, 0, 1), (1.5, 1, 1), (0.5, 2, 1), (-0.5, 1, 1), (3, 0, 1), (4, 0, 1),
             (4, 1, 1), (3, 1, 1)]
    p2 = piece(penta, [], [], [], [[0, 1, 2, 3, 4], [5, 6, 7, 8]])
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" '
                'byte_order="LittleEndian">\n<PolyData>\n%s%s</PolyData>\n</VTKFile>\n' % (p1, p2))


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
        if len(sys.argv) > 5:
            # raw appended data, little-endian, UInt64 headers: VTK's own layout for big files
            vtu_appended(sys.argv[5], m, "raw", False, False, "UInt64")
    elif len(sys.argv) > 1 and sys.argv[1] == "--attributes":
        attributes(sys.argv[2] if len(sys.argv) > 2 else OUT)
    else:
        corpus(sys.argv[1] if len(sys.argv) > 1 else OUT)
        attributes(sys.argv[1] if len(sys.argv) > 1 else OUT)
