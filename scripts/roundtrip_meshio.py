#!/usr/bin/env python3
"""OFF round trip through an independent reader and writer (meshio).

For each triangle-mesh .spx given (default: the triangle datasets found under
../shared/datasets/small and $STARPLEX_DATA/small):
  1. starplex writes OFF:   starplex convert X.spx X.off
     meshio reads X.off; vertex and face counts, coordinates (exactly) and faces (in order) must
     equal those of X.spx, parsed here by a small independent .spx parser.
  2. meshio writes OFF from the same arrays; starplex reads it back to .spx
     (starplex convert meshio.off back.spx) and back.spx must equal X.spx the same way.

meshio's OFF reader only handles 3D triangle meshes, so other complexes are skipped (said so).

Usage: /work/data/.venv/bin/python scripts/roundtrip_meshio.py [--bin target/debug/starplex] [X.spx ...]
Exit status 0 when every file passes, 1 otherwise.
"""
import argparse
import glob
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_spx(path):
    """Minimal independent .spx parser: (coords n x d, [(type, k, cells)])."""
    with open(path) as f:
        lines = (l.split("#", 1)[0].strip() for l in f)
        lines = (l for l in lines if l)
        head = next(lines).split()
        assert head == ["SPX", "1"], f"{path}: bad header {head}"
        d, nv, nc = map(int, next(lines).split())
        coords = np.array([[float(x) for x in next(lines).split()] for _ in range(nv)]).reshape(nv, d)
        blocks = []
        for _ in range(nc):
            t = next(lines).split()
            typ, k, v = t[0], int(t[1]), [int(x) for x in t[2:]]
            assert len(v) == k
            if blocks and blocks[-1][0] == typ and blocks[-1][1] == k:
                blocks[-1][2].append(v)
            else:
                blocks.append((typ, k, [v]))
    return coords, [(t, k, np.array(c, dtype=np.int64)) for t, k, c in blocks]


def compare(name, what, coords, tris, ref_coords, ref_tris):
    problems = []
    if coords.shape != ref_coords.shape:
        problems.append(f"vertex array {coords.shape} != {ref_coords.shape}")
    elif not np.array_equal(coords, ref_coords):
        bad = np.argwhere(coords != ref_coords)[0]
        problems.append(f"coordinate {tuple(bad)} differs: {coords[tuple(bad)]!r} != {ref_coords[tuple(bad)]!r}")
    if tris.shape != ref_tris.shape:
        problems.append(f"face array {tris.shape} != {ref_tris.shape}")
    elif not np.array_equal(tris, ref_tris):
        bad = np.argwhere((tris != ref_tris).any(axis=1))[0][0]
        problems.append(f"face {bad} differs: {tris[bad]} != {ref_tris[bad]}")
    status = "OK  " if not problems else "FAIL"
    print(f"{status} {name}: {what}: {coords.shape[0]} vertices, {tris.shape[0]} faces"
          + ("" if not problems else " -- " + "; ".join(problems)))
    return not problems


def default_inputs():
    found = {}
    dirs = [os.path.join(ROOT, "..", "shared", "datasets", "small"), "/work/shared/datasets/small"]
    if os.environ.get("STARPLEX_DATA"):
        dirs += glob.glob(os.path.join(os.environ["STARPLEX_DATA"], "small", "*"))
    for d in dirs:
        for p in sorted(glob.glob(os.path.join(d, "tri_*.spx"))):
            found.setdefault(os.path.basename(p), p)
    return sorted(found.values())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "target", "debug", "starplex"))
    ap.add_argument("files", nargs="*")
    a = ap.parse_args()
    files = a.files or default_inputs()
    if not files:
        print("no input .spx files found", file=sys.stderr)
        return 1
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        for spx in files:
            name = os.path.basename(spx)
            coords, blocks = read_spx(spx)
            if coords.shape[1] != 3 or [(t, k) for t, k, _ in blocks] != [("tri", 3)]:
                print(f"SKIP {name}: meshio's OFF reader handles only 3D triangle meshes "
                      f"(this has ambient {coords.shape[1]}, blocks {[(t, k) for t, k, _ in blocks]})")
                continue
            tris = blocks[0][2]
            # 1. starplex writes, meshio reads.
            off = os.path.join(tmp, name.replace(".spx", ".off"))
            subprocess.run([a.bin, "--quiet", "convert", spx, off], check=True)
            m = meshio.read(off)
            cells = [c for c in m.cells if c.type == "triangle"]
            mt = cells[0].data.astype(np.int64) if cells else np.zeros((0, 3), np.int64)
            ok &= compare(name, "starplex OFF -> meshio", np.asarray(m.points, float), mt, coords, tris)
            # 2. meshio writes, starplex reads.
            moff = os.path.join(tmp, "meshio_" + name.replace(".spx", ".off"))
            meshio.write(moff, meshio.Mesh(coords, [("triangle", tris)]))
            back = os.path.join(tmp, "back_" + name)
            subprocess.run([a.bin, "--quiet", "convert", moff, back], check=True)
            bc, bb = read_spx(back)
            bt = bb[0][2] if bb else np.zeros((0, 3), np.int64)
            # meshio writes coordinates with limited precision: compare those to 1e-12 relative.
            same_shape = bc.shape == coords.shape
            close = same_shape and np.allclose(bc, coords, rtol=1e-12, atol=0)
            ok &= compare(name, "meshio OFF -> starplex (faces exact)", coords if close else bc, bt, coords, tris)
            if not close:
                print(f"FAIL {name}: meshio OFF -> starplex: coordinates differ beyond 1e-12 relative")
                ok = False
    print("all passed" if ok else "FAILURES")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
