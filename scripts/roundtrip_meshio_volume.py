#!/usr/bin/env python3
"""Independent check of starplex's Medit, legacy VTK and gmsh (4.1 and 2.2) writers: convert datasets' .spx files
with the starplex CLI and read the outputs back with meshio, comparing points and cells per type.

Usage (from the repository root, after `cargo build -p starplex-cli`):
    /work/data/.venv/bin/python scripts/roundtrip_meshio_volume.py [NAME ...]
        [--data DIR] [--bin target/debug/starplex] [--keep DIR]

NAME defaults to mixed_plate_s tet_elephant hex_knot1; each is looked up as DIR/small/NAME/NAME.spx
(DIR defaults to $STARPLEX_DATA or /work/data). Prints one JSON line per dataset and format and
exits with status 1 if anything differs.

meshio's conventions, which this check accounts for: meshio keeps wedges in gmsh's prism order
internally, converts them from/to VTK's wedge order in its VTK reader/writer
([0, 2, 1, 3, 5, 4]), and reads gmsh and Medit prisms as they are written. starplex writes VTK
order to .vtk and .mesh and gmsh order to .msh, so the expected meshio wedge is the starplex prism
permuted for .vtk and .msh and unchanged for .mesh.

When the gmsh Python module is installed, the written .msh is also opened by gmsh itself and the
number of elements it finds inverted is reported (informational).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

PRISM_PERM = [0, 2, 1, 3, 5, 4]
MESHIO_TYPE = {
    "line": "line",
    "tri": "triangle",
    "quad": "quad",
    "tet": "tetra",
    "pyramid": "pyramid",
    "prism": "wedge",
    "hex": "hexahedron",
}


def read_spx(path):
    """Points (n, d) and {spx type: int array (m, k)} in file order."""
    with open(path) as f:
        lines = (l for l in f if l.strip() and not l.lstrip().startswith("#"))
        head = next(lines).split()
        assert head[:2] == ["SPX", "1"], head
        d, nv, nc = map(int, next(lines).split())
        pts = np.array([[float(x) for x in next(lines).split()] for _ in range(nv)]).reshape(nv, d)
        cells = {}
        for _ in range(nc):
            t = next(lines).split()
            cells.setdefault(t[0], []).append([int(x) for x in t[2:]])
    return pts, {t: np.array(c, dtype=np.int64) for t, c in cells.items()}


def meshio_cells(m):
    out = {}
    for block in m.cells:
        out.setdefault(block.type, []).append(np.asarray(block.data, dtype=np.int64))
    return {t: np.concatenate(v) for t, v in out.items()}


def gmsh_inverted(path):
    """Per element type, how many elements gmsh itself finds inverted (minSJ < 0) in `path`, or
    None when the gmsh module is not installed. Informational: it says whether the cells handed
    to the writer had gmsh's orientation (for the datasets' .spx, whose prisms are stored in
    gmsh's order rather than VTK's, every prism shows up here)."""
    try:
        import gmsh
    except ImportError:
        return None
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        out = {}
        types, etags, _ = gmsh.model.mesh.getElements()
        for t, e in zip(types, etags):
            name, dim = gmsh.model.mesh.getElementProperties(t)[:2]
            if dim == 3 and len(e):
                q = np.asarray(gmsh.model.mesh.getElementQualities(e, "minSJ"))
                out[name] = int((q < 0).sum())
        return out
    finally:
        gmsh.finalize()


def check(name, spx, binary, workdir):
    pts, cells = read_spx(spx)
    results = []
    for fmt in ["mesh", "vtk", "msh", "msh22"]:
        ext = "msh" if fmt == "msh22" else fmt
        out = os.path.join(workdir, f"{name}.{fmt}.{ext}")
        p = subprocess.run([binary, "convert", spx, out, "--to", fmt], capture_output=True, text=True)
        rec = {"dataset": name, "format": fmt}
        if p.returncode != 0:
            rec.update(ok=False, error=f"starplex convert failed: {p.stderr.strip()}")
            results.append(rec)
            continue
        m = meshio.read(out)
        mp = np.asarray(m.points, dtype=float)
        want_pts = np.zeros((len(pts), 3))
        want_pts[:, : pts.shape[1]] = pts
        same_shape = mp.shape == want_pts.shape
        max_diff = float(np.abs(mp - want_pts).max()) if same_shape and len(pts) else 0.0
        rec["points"] = {"n": int(len(mp)), "expected": int(len(pts)), "max_abs_diff": max_diff}
        got = meshio_cells(m)
        per_type = {}
        ok = same_shape and max_diff == 0.0
        for t, c in cells.items():
            mt = MESHIO_TYPE.get(t)
            want = c
            if t == "prism" and ext in ("vtk", "msh"):
                want = c[:, PRISM_PERM]
            g = got.pop(mt, np.zeros((0, c.shape[1]), dtype=np.int64))
            equal = g.shape == want.shape and bool(np.array_equal(g, want))
            per_type[t] = {"n": int(len(g)), "expected": int(len(c)), "identical": equal}
            ok &= equal
        for t, g in got.items():
            per_type[f"unexpected {t}"] = {"n": int(len(g))}
            ok = False
        rec["cells"] = per_type
        if ext == "msh":
            rec["gmsh_negative_jacobians"] = gmsh_inverted(out)
        rec["ok"] = bool(ok)
        results.append(rec)
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("names", nargs="*", default=["mixed_plate_s", "tet_elephant", "hex_knot1"])
    ap.add_argument("--data", default=os.environ.get("STARPLEX_DATA", "/work/data"))
    ap.add_argument("--bin", default=os.path.join("target", "debug", "starplex"))
    ap.add_argument("--keep", help="write the converted files here instead of a temporary directory")
    a = ap.parse_args()
    if not os.path.exists(a.bin):
        sys.exit(f"{a.bin} not found: run `cargo build -p starplex-cli` first")
    all_ok = True
    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep or tmp
        os.makedirs(work, exist_ok=True)
        for name in a.names:
            spx = os.path.join(a.data, "small", name, f"{name}.spx")
            if not os.path.exists(spx):
                print(json.dumps({"dataset": name, "skipped": f"{spx} not found"}))
                continue
            for rec in check(name, spx, a.bin, work):
                all_ok &= rec.get("ok", False)
                print(json.dumps(rec))
    sys.exit(0 if all_ok else 1)


if __name__ == "__main__":
    main()
