#!/usr/bin/env python3
"""Reads the output of starplex's newer writers back with independent readers and compares it with
what starplex wrote (reference.json, written beside the files by the test `own_outputs_for_meshio`
of crates/starplex/tests/suite/io_writers_more.rs):

- gmsh 4.1 ascii and binary with physical/geometrical tags as entities, and gmsh 2.2 binary with
  them as element tags: meshio (points, cells, gmsh:physical, gmsh:geometrical, data) and gmsh's
  own API (physical group of every entity);
- PLY with an `edge` element (ascii and binary): trimesh's PLY parser (its raw element arrays);
  meshio 5.3.5 has no `edge` element (reported, not counted);
- legacy VTK POLYDATA: meshio 5.3.5 reads no POLYDATA and the venv has no `vtk` module
  (reported, not counted).

Usage: STARPLEX_WRITERS_OUT=DIR cargo test -p starplex --test suite io_writers_more::own_outputs
       /work/data/.venv/bin/python scripts/check_writers_more.py DIR
"""
import json
import os
import sys

import meshio
import numpy as np

d = sys.argv[1]
ref = json.load(open(os.path.join(d, "reference.json")))
bad = 0


def report(what, ok):
    global bad
    print(what, "OK" if ok else "DIFFERS")
    bad += not ok


def values(col):
    v = np.array([np.nan if x is None else x for x in col["values"]], dtype=float)
    return v.reshape(-1, col["components"]) if col["components"] > 1 else v


def same(got, want):
    got = np.asarray(got, dtype=float).reshape(np.shape(want))
    return bool(np.allclose(got, want, equal_nan=True))


MESHIO_KIND = {"line": "line", "tri": "triangle", "tet": "tetra", "quad": "quad"}

# gmsh: meshio
g = ref["gmsh"]
pts = np.array(g["points"]).reshape(-1, 3)
want_blocks = [(MESHIO_KIND.get(k, k), np.array(v)) for k, v in g["blocks"]]
for f in ["tags_41.msh", "tags_41_bin.msh", "tags_22_bin.msh"]:
    try:
        m = meshio.read(os.path.join(d, f))
    except Exception as ex:  # noqa: BLE001
        report("meshio %s: cannot read it (%s: %s)" % (f, type(ex).__name__, ex), False)
        continue
    ok = same(m.points, pts)
    got = {}
    for c in m.cells:
        got.setdefault(c.type, []).append(c.data)
    for kind, v in want_blocks:
        n = {"line": 2, "triangle": 3, "tetra": 4, "quad": 4}[kind]
        ok &= same(np.concatenate(got[kind]), v.reshape(-1, n))
    ok &= same(m.point_data["T"], values(g["attrs"]["vertex"]["T"]))
    for name, col in g["attrs"]["cell"].items():
        if f == "tags_22_bin.msh" and name == "stress":
            continue  # written without element data (meshio 5.3.5 mis-splits 2.2 $ElementData)
        ok &= same(np.concatenate(m.cell_data[name]), values(col))
    report("meshio %s points, cells, cell_data %s" % (f, sorted(m.cell_data)), ok)

# gmsh: gmsh's own reader
try:
    import gmsh
except ImportError:
    print("gmsh module missing: skipped")
else:
    phys = values(g["attrs"]["cell"]["gmsh:physical"])
    geom = values(g["attrs"]["cell"]["gmsh:geometrical"])
    for f in ["tags_41.msh", "tags_41_bin.msh", "tags_22_bin.msh"]:
        gmsh.initialize(["-v", "0"])
        gmsh.open(os.path.join(d, f))
        ok = True
        tags_seen = []
        for dim, tag in gmsh.model.getEntities():
            types, etags, _ = gmsh.model.mesh.getElements(dim, tag)
            p = list(gmsh.model.getPhysicalGroupsForEntity(dim, tag))
            for et in etags:
                for e in et:
                    i = int(e) - 1
                    tags_seen.append(i)
                    ok &= geom[i] == tag
                    ok &= (p == [phys[i]]) if phys[i] != 0 else (p == [])
        ok &= sorted(tags_seen) == list(range(len(phys)))
        gmsh.finalize()
        report("gmsh %s: every element on its entity, every entity in its physical group" % f, ok)

# PLY with edges: trimesh's parser
s = ref["surface"]
edges = [np.array(v).reshape(-1, 2) for k, v in s["blocks"] if k == "line"]
edges = np.concatenate(edges)
n_edges = len(edges)
# cell ids of the edges (blocks in order)
ids, start = [], 0
for k, v in s["blocks"]:
    n = len(v) // {"line": 2, "tri": 3, "quad": 4}[k]
    if k == "line":
        ids.extend(range(start, start + n))
    start += n
ids = np.array(ids)
try:
    import trimesh
except ImportError:
    print("trimesh missing: skipped")
else:
    for f in ["edges_ascii.ply", "edges_bin.ply"]:
        try:
            t = trimesh.load(os.path.join(d, f), process=False)
        except Exception as ex:  # noqa: BLE001
            report("trimesh %s: cannot read it (%s: %s)" % (f, type(ex).__name__, ex), False)
            continue
        raw = t.metadata["_ply_raw"]
        e = raw["edge"]["data"]
        ok = same(np.stack([e["vertex1"], e["vertex2"]], axis=1), edges)
        for name, col in s["attrs"]["cell"].items():
            v = values(col)[ids]
            if col["components"] == 1:
                ok &= same(e[name], v)
            else:
                ok &= same(np.stack([e["%s_%d" % (name, j)] for j in range(col["components"])], axis=1), v)
        for name, col in s["attrs"]["vertex"].items():
            ok &= same(raw["vertex"]["data"][name], values(col))
        ok &= same(t.vertices, np.array(s["points"]).reshape(-1, 3))
        report("trimesh %s: edge element (vertex1, vertex2, %s), vertex properties" % (f, ", ".join(s["attrs"]["cell"])), ok)
    try:
        meshio.read(os.path.join(d, "edges_ascii.ply"))
    except BaseException as ex:  # noqa: BLE001 (meshio exits on some errors)
        print("meshio edges_ascii.ply: meshio 5.3.5 has no PLY edge element (%s): not counted" % type(ex).__name__)
try:
    meshio.read(os.path.join(d, "poly.vtk"))
except BaseException as ex:  # noqa: BLE001
    print("meshio poly.vtk: meshio 5.3.5 reads no legacy POLYDATA (%s): not counted" % type(ex).__name__)
sys.exit(1 if bad else 0)
