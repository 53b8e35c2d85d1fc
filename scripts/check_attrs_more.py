#!/usr/bin/env python3
"""Reads starplex's own PLY/OFF/gmsh output (written by the test
`own_outputs_for_independent_readers` of crates/starplex/tests/suite/io_attrs_more.rs) back with meshio
and trimesh and compares every attribute with the reference columns (more_attrs.json).

Usage: STARPLEX_ATTR_OUT=DIR cargo test -p starplex --test suite io_attrs_more::own_outputs
       /work/data/.venv/bin/python scripts/check_attrs_more.py DIR
"""
import json
import os
import sys

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REF = os.path.join(HERE, "..", "crates", "starplex", "tests", "data", "io", "more_attrs.json")

d = sys.argv[1]
ref = json.load(open(REF))
bad = 0


def report(what, ok):
    global bad
    print(what, "OK" if ok else "DIFFERS")
    bad += not ok


def same(got, rows):
    want = np.array(rows, dtype=float)
    got = np.asarray(got, dtype=float).reshape(want.shape)
    return bool(np.allclose(got, want, equal_nan=True))


# PLY: the trimesh file written by starplex
want = ref["trimesh_binary.ply"]
for f in ["out_bin.ply", "out_ascii.ply"]:
    try:
        m = meshio.read(os.path.join(d, f))
    except TypeError as e:
        # meshio 5.3.5 reads a binary PLY face property as one number (_read_binary), whoever
        # wrote it: trimesh's own binary file fails the same way
        try:
            meshio.read(os.path.join(os.path.dirname(REF), "trimesh_binary.ply"))
        except TypeError:
            print("meshio %s: cannot read binary PLY face properties (%s), nor trimesh's own file" % (f, e))
        else:
            report("meshio %s" % f, False)
    else:
        ok = all(same(m.point_data[k], v) for k, v in want["vertex"].items())
        ok &= all(same(m.cell_data[k][0], v) for k, v in want["cell"].items())
        report("meshio %s point_data %s cell_data %s" % (f, sorted(m.point_data), sorted(m.cell_data)), ok)
    try:
        import trimesh
    except ImportError:
        continue
    t = trimesh.load(os.path.join(d, f), process=False)
    cols = np.asarray(t.visual.vertex_colors)
    ok = all(same(cols[:, i], want["vertex"][c]) for i, c in enumerate(["red", "green", "blue", "alpha"]))
    raw = t.metadata["_ply_raw"]  # trimesh keeps the properties it parsed here
    ok &= same(raw["vertex"]["data"]["quality"], want["vertex"]["quality"])
    ok &= same(raw["face"]["data"]["label"], want["cell"]["label"])
    report("trimesh %s colours, quality, label" % f, ok)
# gmsh: meshio's binary 2.2 file written back by starplex as 2.2 and 4.1 ascii
want = ref["meshio_22_bin.msh"]
for f, tags in [("out_22.msh", True), ("out_41.msh", False)]:
    m = meshio.read(os.path.join(d, f))
    ok = all(same(m.point_data[k], v) for k, v in want["vertex"].items())
    for k, v in want["cell"].items():
        if k == "gmsh:geometrical" and not tags:
            # entity 1 of this file holds two physical groups: 4.1 numbers its entities by
            # physical group instead (Format::Gmsh.dropped_attributes says so)
            continue
        ok &= same(np.concatenate(m.cell_data[k]), v)
    report("meshio %s point_data %s cell_data %s" % (f, sorted(m.point_data), sorted(m.cell_data)), ok)
sys.exit(1 if bad else 0)
