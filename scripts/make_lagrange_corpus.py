#!/usr/bin/env python3
"""Writes VTK's arbitrary-order cells for starplex's tests (crates/starplex/tests/data/io/lg_*).

Needs VTK's Python module (`pip install vtk`). `vtkCellTypeSource` makes the same 2x2x2 block
of cells at order 1 (the linear types) and at orders 2 and 3 (the Lagrange types 68-73 and the
Bezier types 75-80); the higher-order files are written as legacy VTK (binary) and `.vtu`
(appended raw), the linear ones as `.vtu`. starplex reads a higher-order cell as its linear
cell (its first points are the corners), so `crates/starplex/tests/suite/io_higher_order.rs` checks
that every higher-order file's cells, compared by their corners' coordinates, are the linear
file's cells. VTK itself has no arbitrary-order pyramid (types 74 and 81 have no cell class in
VTK 9), so none is written.

The quadratic polygon (type 36: its corners, then one point on each side) is written by hand,
a pentagon and a square, beside the same two polygons as linear type-7 cells.

Usage: scripts/make_lagrange_corpus.py [OUT_DIR]
"""
import os
import sys

import vtk

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    HERE, "..", "crates", "starplex", "tests", "data", "io")

LINEAR = {3: "line", 5: "tri", 9: "quad", 10: "tet", 12: "hex", 13: "wedge"}
# (Lagrange type, Bezier type) -> the linear type with the same corners
HIGHER = {68: 3, 69: 5, 70: 9, 71: 10, 72: 12, 73: 13, 75: 3, 76: 5, 77: 9, 78: 10, 79: 12, 80: 13}


def block(cell_type, order):
    s = vtk.vtkCellTypeSource()
    s.SetCellType(cell_type)
    s.SetCellOrder(order)
    s.SetBlocksDimensions(2, 2, 2)
    s.Update()
    return s.GetOutput()


def write_vtu(grid, path):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()
    w.Write()


def write_vtk(grid, path):
    w = vtk.vtkUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    w.SetFileTypeToBinary()
    w.Write()


def quadratic_polygons():
    """A pentagon and a square sharing a side, as type 36 and as type 7."""
    pts = [(0, 0, 0), (2, 0, 0), (3, 1.5, 0), (1, 3, 0), (-1, 1.5, 0), (2, -2, 0), (0, -2, 0)]
    pentagon = [0, 1, 2, 3, 4]
    square = [1, 0, 6, 5]
    quad = vtk.vtkUnstructuredGrid()
    lin = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    for p in pts:
        points.InsertNextPoint(p)
    lin_points = vtk.vtkPoints()
    lin_points.DeepCopy(points)
    lin.SetPoints(lin_points)
    for poly in (pentagon, square):
        ids = list(poly)
        for i, a in enumerate(poly):  # one point on each side, after the corners
            b = poly[(i + 1) % len(poly)]
            pa, pb = pts[a], pts[b]
            ids.append(points.InsertNextPoint([(x + y) / 2 for x, y in zip(pa, pb)]))
        quad.InsertNextCell(36, len(ids), ids)
        lin.InsertNextCell(7, len(poly), poly)
    quad.SetPoints(points)
    return quad, lin


def main():
    for t, name in LINEAR.items():
        write_vtu(block(t, 1), os.path.join(OUT, f"lg_{name}_o1.vtu"))
    for t, lin in HIGHER.items():
        for order in (2, 3):
            g = block(t, order)
            assert g.GetNumberOfCells() > 0 and g.GetCellType(0) == t, (t, order)
            stem = os.path.join(OUT, f"lg_{t}_o{order}")
            write_vtu(g, stem + ".vtu")
            write_vtk(g, stem + ".vtk")
    quad, lin = quadratic_polygons()
    write_vtu(quad, os.path.join(OUT, "lg_36_o2.vtu"))
    write_vtk(quad, os.path.join(OUT, "lg_36_o2.vtk"))
    write_vtu(lin, os.path.join(OUT, "lg_polygon_o1.vtu"))


if __name__ == "__main__":
    main()
