#!/usr/bin/env python3
"""Writes gmsh's own higher-order meshes for starplex's tests (crates/starplex/tests/data/io/ho_*).

Needs the `gmsh` Python module (`pip install gmsh`). Each mesh is written first at order 1, then
raised with gmsh's `setOrder` (which keeps the corner nodes and their tags and adds the others),
in the four encodings starplex reads: 4.1 and 2.2, ascii and binary. starplex reads a
higher-order element as its first-order cell, so every higher-order file must read as the
order-1 file does (`crates/starplex/tests/suite/io_higher_order.rs`).

- `ho_tet`: tetrahedra of a unit box (orders 2 and 3: types 11 and 29, with 9/21 triangles);
- `ho_hex`: a transfinite, recombined 2x2x2 box of hexahedra (order 2: complete 27-node
  hexahedra, type 12, and serendipity 20-node ones, type 17, with 9/8-node quads);
- `ho_prism`: a 2-layer extrusion of a triangulated square (order 2: 18- and 15-node prisms).

With meshio installed it also writes the order-2 meshes as legacy VTK (ascii) and `.vtu` (base64
binary), whose quadratic cell types (22-29, 32) starplex reads as their linear cells.

Usage: scripts/make_higher_order_corpus.py [OUT_DIR]
"""
import os
import sys

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    HERE, "..", "crates", "starplex", "tests", "data", "io")


def write_all(name, orders, incomplete=False):
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1 if incomplete else 0)
    for order in orders:
        if order > 1:
            gmsh.model.mesh.setOrder(order)
        for version, binary in [(4.1, 0), (4.1, 1), (2.2, 0), (2.2, 1)]:
            if order == 1 and (version, binary) != (4.1, 0):
                continue
            gmsh.option.setNumber("Mesh.MshFileVersion", version)
            gmsh.option.setNumber("Mesh.Binary", binary)
            enc = f"{'41' if version > 3 else '22'}_{'bin' if binary else 'ascii'}"
            suffix = "o1" if order == 1 else f"o{order}{'s' if incomplete else ''}_{enc}"
            gmsh.write(os.path.join(OUT, f"{name}_{suffix}.msh"))


def tets():
    gmsh.model.add("ho_tet")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMin", 1.0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 1.0)
    gmsh.model.mesh.generate(3)
    write_all("ho_tet", [1, 2])
    gmsh.model.mesh.setOrder(1)
    write_all("ho_tet", [3])


def hexes(incomplete):
    gmsh.model.add("ho_hex")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    for dim, tag in gmsh.model.getEntities(1):
        gmsh.model.mesh.setTransfiniteCurve(tag, 3)
    for dim, tag in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(tag)
        gmsh.model.mesh.setRecombine(2, tag)
    for dim, tag in gmsh.model.getEntities(3):
        gmsh.model.mesh.setTransfiniteVolume(tag)
    gmsh.model.mesh.generate(3)
    if incomplete:
        write_all("ho_hex", [2], incomplete=True)
    else:
        write_all("ho_hex", [1, 2])


def prisms(incomplete):
    gmsh.model.add("ho_prism")
    s = gmsh.model.occ.addRectangle(0, 0, 0, 1, 1)
    gmsh.model.occ.extrude([(2, s)], 0, 0, 1, numElements=[2], recombine=True)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMin", 1.0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 1.0)
    gmsh.model.mesh.generate(3)
    if incomplete:
        write_all("ho_prism", [2], incomplete=True)
    else:
        write_all("ho_prism", [1, 2])


gmsh.initialize(["", "-v", "0"])
tets()
gmsh.clear()
hexes(False)
gmsh.clear()
hexes(True)
gmsh.clear()
prisms(False)
gmsh.clear()
prisms(True)
gmsh.finalize()

# the same meshes through meshio into legacy VTK and VTK XML (quadratic VTK cell types); meshio
# reads gmsh's tetra10/hexahedron27/hexahedron20/wedge18 and writes them with VTK's point order
try:
    import meshio
except ImportError:
    meshio = None
if meshio is not None:
    for name in ["ho_tet_o2", "ho_hex_o2", "ho_hex_o2s", "ho_prism_o2"]:
        m = meshio.read(os.path.join(OUT, f"{name}_41_ascii.msh"))
        m = meshio.Mesh(m.points, [(c.type, c.data) for c in m.cells if c.type != "vertex"])
        meshio.write(os.path.join(OUT, f"{name}.vtk"), m, binary=False)
        meshio.write(os.path.join(OUT, f"{name}.vtu"), m, binary=True)
