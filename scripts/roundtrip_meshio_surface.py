#!/usr/bin/env python3
"""Independent check of the PLY and OBJ writers of starplex.

For each dataset: `starplex convert X.spx out.ply` and `out.obj` (the CLI), then read both files with
meshio (an independent reader) and compare with the .spx read here: coordinates must be equal
(exactly: both writers keep every f64 bit) and the cells of each type must be the same vertex
lists in the same order. Prints one JSON line per (dataset, format) and exits non-zero on any
mismatch.

    /work/data/.venv/bin/python scripts/roundtrip_meshio_surface.py \
        [--bin target/debug/starplex] [--data /work/data] [tri_elephant quad_elephant ...]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

SPX_TO_MESHIO = {"tri": "triangle", "quad": "quad"}


def read_spx(path):
    """(V, [(type, cells)]) of a .spx file; blocks are runs of one type."""
    with open(path) as f:
        lines = [l for l in (x.strip() for x in f) if l and not l.startswith("#")]
    assert lines[0].split()[0] == "SPX", path
    d, nv, nc = map(int, lines[1].split())
    V = np.array([[float(t) for t in l.split()] for l in lines[2:2 + nv]], dtype=np.float64).reshape(nv, d)
    blocks, cur, rows = [], None, []
    for l in lines[2 + nv:2 + nv + nc]:
        t = l.split()
        if t[0] != cur:
            if cur is not None:
                blocks.append((cur, np.array(rows, dtype=np.int64)))
            cur, rows = t[0], []
        rows.append([int(x) for x in t[2:]])
    if cur is not None:
        blocks.append((cur, np.array(rows, dtype=np.int64)))
    return V, blocks


def by_type(blocks):
    """type -> all cells of that type, in file order."""
    out = {}
    for t, c in blocks:
        out.setdefault(t, []).append(np.asarray(c, dtype=np.int64))
    return {t: np.concatenate(v) for t, v in out.items()}


def compare(V, blocks, mesh):
    problems = []
    P = np.asarray(mesh.points, dtype=np.float64)
    if P.shape != V.shape:
        if P.shape[0] == V.shape[0] and V.shape[1] == 2 and P.shape[1] == 3 and not P[:, 2].any():
            P = P[:, :2]
        else:
            problems.append(f"points shape {P.shape} != {V.shape}")
    if not problems and not np.array_equal(P, V):
        bad = int(np.argmax(np.any(P != V, axis=1)))
        problems.append(f"coordinates differ, first at vertex {bad}: {P[bad].tolist()} vs {V[bad].tolist()}"
                        f" (max abs diff {float(np.max(np.abs(P - V))):.3g})")
    ours = by_type([(SPX_TO_MESHIO.get(t, t), c) for t, c in blocks])
    theirs = by_type([(b.type, b.data) for b in mesh.cells])
    if sorted(ours) != sorted(theirs):
        problems.append(f"cell types {sorted(theirs)} != {sorted(ours)}")
    else:
        for t in ours:
            if not np.array_equal(ours[t], theirs[t]):
                problems.append(f"{t} cells differ ({len(theirs[t])} read, {len(ours[t])} expected)")
    return problems


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(root, "target", "debug", "starplex"))
    ap.add_argument("--data", default=os.environ.get("STARPLEX_DATA", "/work/data"))
    ap.add_argument("datasets", nargs="*", default=["tri_elephant", "quad_elephant"])
    a = ap.parse_args()
    failed = 0
    with tempfile.TemporaryDirectory(prefix="starplex-meshio-") as tmp:
        for name in a.datasets:
            spx = os.path.join(a.data, "small", name, name + ".spx")
            V, blocks = read_spx(spx)
            for ext in ("ply", "obj"):
                out = os.path.join(tmp, f"{name}.{ext}")
                cp = subprocess.run([a.bin, "convert", spx, out], capture_output=True, text=True)
                rec = {"dataset": name, "format": ext, "n_vertices": int(V.shape[0]),
                       "n_cells": int(sum(len(c) for _, c in blocks))}
                if cp.returncode != 0:
                    rec.update(ok=False, problems=[f"starplex convert failed: {cp.stderr.strip()}"])
                else:
                    rec["bytes"] = os.path.getsize(out)
                    try:
                        mesh = meshio.read(out)
                        problems = compare(V, blocks, mesh)
                    except Exception as e:  # noqa: BLE001 - report any reader failure
                        problems = [f"meshio failed: {type(e).__name__}: {e}"]
                    rec.update(ok=not problems, problems=problems, meshio=meshio.__version__)
                failed += not rec["ok"]
                print(json.dumps(rec), flush=True)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
