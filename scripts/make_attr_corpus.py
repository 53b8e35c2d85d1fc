#!/usr/bin/env python3
"""Writes the attribute test corpus for PLY, OFF and gmsh data sections
(crates/starplex/tests/data/io/, read by crates/starplex/tests/suite/io_attrs_more.rs) with independent
writers, and `more_attrs.json`: for every file, the vertex and cell columns a reader must find
(name -> rows, cells in file order).

- gmsh: gmsh's own writer (the `gmsh` Python API: a meshed box with the physical volume 5, a
  node field `temperature` of two time steps (x + 2y at step 0, 10x at step 1) and an element
  field `flux` of 3 components (tag, 0.5, -1); 2.2 and 4.1, ascii and binary: `gmsh_*.msh`,
  checked by relation, not listed in the json) and meshio's binary writer (2.2 with a line,
  4.1 tetrahedra only; meshio 5.3.5's ascii data sections are broken under numpy 2:
  `np.float64(3.0)`).
- PLY: trimesh (ascii and binary: uchar colours, a float vertex attribute, an int face
  attribute), meshio (ascii and binary: point data), and a hand-written big-endian file with
  normals, a `{base}_0..` vector, face and `edge` elements with their own properties.

Needs meshio, trimesh, gmsh and numpy (/work/data/.venv has them).
Usage: scripts/make_attr_corpus.py [OUT_DIR]
"""
import json
import os
import struct
import sys

import meshio
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "starplex", "tests", "data", "io")


def rows(a, n):
    return np.asarray(a).reshape(n, -1).tolist()


def ply(out, ref):
    import trimesh
    m = trimesh.creation.icosphere(subdivisions=0)
    nv, nf = len(m.vertices), len(m.faces)
    rgba = np.array([[i * 10 % 256, i * 7 % 256, 255 - i, 200] for i in range(nv)], dtype=np.uint8)
    m.visual.vertex_colors = rgba
    m.vertex_attributes["quality"] = np.arange(nv, dtype=np.float32) / 4
    m.face_attributes["label"] = (np.arange(nf) % 3).astype(np.int32)
    want = {"vertex": {c: rows(rgba[:, i], nv) for i, c in enumerate(["red", "green", "blue", "alpha"])},
            "cell": {"label": rows(np.arange(nf) % 3, nf)}}
    want["vertex"]["quality"] = rows(np.arange(nv) / 4, nv)
    for enc in ["ascii", "binary"]:
        name = "trimesh_%s.ply" % enc
        with open(os.path.join(out, name), "wb") as f:
            f.write(trimesh.exchange.ply.export_ply(m, encoding=enc, include_attributes=True))
        ref[name] = want
    pd = {"temp": np.arange(nv) / 3.0, "id": np.arange(nv, dtype=np.int32) * 3}
    mm = meshio.Mesh(m.vertices, [("triangle", m.faces)], point_data=pd)
    for binary in [False, True]:
        name = "meshio_%s.ply" % ("bin" if binary else "ascii")
        meshio.ply.write(os.path.join(out, name), mm, binary=binary)
        ref[name] = {"vertex": {k: rows(v, nv) for k, v in pd.items()}, "cell": {}}

    # big-endian by hand: 4 vertices of a quad + 2 of a free edge
    pts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (3, 3, 3), (4, 3, 3)]
    hdr = ("ply\nformat binary_big_endian 1.0\nelement vertex 6\n"
           "property float x\nproperty float y\nproperty float z\n"
           "property float nx\nproperty float ny\nproperty float nz\n"
           "property short uv_0\nproperty short uv_1\nproperty uchar red\n"
           "element face 2\nproperty list uchar uint vertex_indices\nproperty int label\n"
           "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
           "property int label\nproperty double crease\n"
           "end_header\n")
    body = b""
    for i, p in enumerate(pts):
        body += struct.pack(">3f3f2hB", *p, 0.0, 0.0, 1.0, i, -i, 40 * i)
    body += struct.pack(">B3Ii", 3, 0, 1, 2, 7) + struct.pack(">B3Ii", 3, 0, 2, 3, -8)
    body += struct.pack(">iiid", 4, 5, 9, 0.5)
    with open(os.path.join(out, "hand_be.ply"), "wb") as f:
        f.write(hdr.encode() + body)
    ref["hand_be.ply"] = {
        "vertex": {"nx": [[0.0]] * 6, "ny": [[0.0]] * 6, "nz": [[1.0]] * 6,
                   "uv": [[i, -i] for i in range(6)], "red": [[40 * i] for i in range(6)]},
        "cell": {"label": [[7], [-8], [9]], "crease": [[None], [None], [0.5]]}}


def gmsh_files(out, ref):
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("b")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(3, [1], 5)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 1.0)
    gmsh.model.mesh.generate(3)
    ntags, coords, _ = gmsh.model.mesh.getNodes()
    _, etags, _ = gmsh.model.mesh.getElements(3)
    t = gmsh.view.add("temperature")
    gmsh.view.addModelData(t, 0, "b", "NodeData", list(ntags),
                           [[coords[3 * i] + 2 * coords[3 * i + 1]] for i in range(len(ntags))], time=0.0)
    gmsh.view.addModelData(t, 1, "b", "NodeData", list(ntags),
                           [[coords[3 * i] * 10] for i in range(len(ntags))], time=1.0)
    v = gmsh.view.add("flux")
    gmsh.view.addModelData(v, 0, "b", "ElementData", list(etags[0]),
                           [[float(e), 0.5, -1.0] for e in etags[0]])
    gmsh.option.setNumber("PostProcessing.SaveMesh", 0)
    for ver in ["2.2", "4.1"]:
        gmsh.option.setNumber("Mesh.MshFileVersion", float(ver))
        for binary in [0, 1]:
            gmsh.option.setNumber("Mesh.Binary", binary)
            name = os.path.join(out, "gmsh_%s_%s.msh" % (ver.replace(".", ""), "bin" if binary else "ascii"))
            gmsh.write(name)
            for view in [t, v]:
                gmsh.view.write(view, name, append=True)
    gmsh.finalize()

    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [2, 2, 2], [3, 2, 2]], float)
    tets = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])
    for ver, cells, n in [("2.2", [("tetra", tets), ("line", np.array([[5, 6]]))], 7),
                          ("4.1", [("tetra", tets)], 5)]:
        nc = sum(len(c) for _, c in cells)
        pd = {"T": np.arange(n) / 2.0, "vel": np.arange(3.0 * n).reshape(n, 3)}
        cd = {"mat": np.arange(nc) + 3.0, "gmsh:physical": np.array([1, 2, 7][:nc]),
              "gmsh:geometrical": np.array([1, 1, 2][:nc])}
        split = np.cumsum([len(c) for _, c in cells])[:-1]
        m = meshio.Mesh(pts[:n], cells, point_data=pd,
                        cell_data={k: np.split(v, split) for k, v in cd.items()})
        name = "meshio_%s_bin.msh" % ver.replace(".", "")
        meshio.gmsh.write(os.path.join(out, name), m, fmt_version=ver, binary=True)
        ref[name] = {"vertex": {k: rows(v, n) for k, v in pd.items()},
                     "cell": {k: rows(v, nc) for k, v in cd.items()}}
        if ver == "4.1":
            # meshio's 4.1 writer drops per-element physical tags (it writes no physical group)
            # and gives every element of the block the entity tag 1
            del ref[name]["cell"]["gmsh:physical"]
            ref[name]["cell"]["gmsh:geometrical"] = [[1]] * nc


def main(out):
    ref = {}
    ply(out, ref)
    gmsh_files(out, ref)
    with open(os.path.join(out, "more_attrs.json"), "w") as f:
        json.dump(ref, f, indent=0)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else OUT)
