#!/usr/bin/env python3
"""Writes the attribute test corpus for PLY, OFF and gmsh data sections
(crates/starplex/tests/data/io/, read by crates/starplex/tests/io_attrs_more.rs) with independent
writers, and `more_attrs.json`: for every file, the vertex and cell columns a reader must find
(name -> rows, cells in file order).

- PLY: trimesh (ascii and binary: uchar colours, a float vertex attribute, an int face
  attribute), meshio (ascii and binary: point data), and a hand-written big-endian file with
  normals, a `{base}_0..` vector, face and `edge` elements with their own properties.

Needs meshio, trimesh and numpy (/work/data/.venv has them).
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


def main(out):
    ref = {}
    ply(out, ref)
    with open(os.path.join(out, "more_attrs.json"), "w") as f:
        json.dump(ref, f, indent=0)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else OUT)
