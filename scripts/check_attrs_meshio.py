#!/usr/bin/env python3
"""Reads starplex's own .vtu/.vtk output back with meshio and VTK and compares every attribute
with the reference columns (tests/data/io/mixed_attrs.json).

Usage: starplex convert crates/starplex/tests/data/io/attrs_b64_zlib.vtu DIR/out.vtu (and out.vtk)
       python scripts/check_attrs_meshio.py DIR      (a venv with meshio, numpy, optionally vtk)
"""
import json
import os
import sys

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REF = os.path.join(HERE, "..", "crates", "starplex", "tests", "data", "io", "mixed_attrs.json")

d = sys.argv[1]
ref = json.load(open(REF))
bad = 0
for f in ["out.vtu", "out.vtk"]:
    m = meshio.read(os.path.join(d, f))
    ok = True
    for k, v in ref["vertex"].items():
        ok &= np.allclose(np.asarray(m.point_data[k]).reshape(len(v), -1), np.array(v))
    for k, v in ref["cell"].items():
        got = np.concatenate([np.asarray(x).reshape(len(x), -1) for x in m.cell_data[k]])
        ok &= np.allclose(got, np.array(v))
    print(f, "meshio reads every attribute equal:", ok)
    bad += not ok
try:
    import vtk
except ImportError:
    print("vtk is not installed: VTK's own readers not tried")
else:
    for f, reader in [("out.vtu", vtk.vtkXMLUnstructuredGridReader),
                      ("out.vtk", vtk.vtkUnstructuredGridReader)]:
        r = reader()
        r.SetFileName(os.path.join(d, f))
        r.Update()
        o = r.GetOutput()
        pd = sorted(o.GetPointData().GetArrayName(i) for i in range(o.GetPointData().GetNumberOfArrays()))
        cd = sorted(o.GetCellData().GetArrayName(i) for i in range(o.GetCellData().GetNumberOfArrays()))
        ok = pd == sorted(ref["vertex"]) and cd == sorted(ref["cell"])
        print("VTK", f, o.GetNumberOfPoints(), "points", o.GetNumberOfCells(), "cells", pd, cd, ok)
        bad += not ok
sys.exit(1 if bad else 0)
