"""Betti numbers with GUDHI on a starplex .spx file (simplicial complexes only), for the
side-by-side comparison in BENCHMARKS.md ("Homology").

    /work/data/.venv/bin/python scripts/bench_homology_gudhi.py FILE.spx

Prints one JSON line: load time (not compared), SimplexTree build time, persistence + Betti
time, number of simplices, Betti numbers. Wrap with /usr/bin/time -v for the peak RSS.
"""
import json
import sys
import time

import numpy as np
import gudhi


def read_spx_cells(path):
    """Top cells of a .spx file as {arity: int32 array}; fast enough for millions of cells."""
    with open(path) as f:
        lines = [l for l in (x.strip() for x in f) if l and not l.startswith('#')]
    d, nv, nc = map(int, lines[1].split())
    by_arity = {}
    for l in lines[2 + nv:2 + nv + nc]:
        t = l.split()
        k = int(t[1])
        if t[0] not in ('line', 'tri', 'tet', 'simplex', 'vertex', 'point'):
            raise SystemExit(f"{path}: {t[0]} cells are not simplices; GUDHI needs simplices")
        by_arity.setdefault(k, []).append(t[2:2 + k])
    return nv, {k: np.array(v, dtype=np.int32) for k, v in by_arity.items()}


def main():
    path = sys.argv[1]
    t0 = time.perf_counter()
    nv, cells = read_spx_cells(path)
    load_s = time.perf_counter() - t0
    t1 = time.perf_counter()
    st = gudhi.SimplexTree()
    for v in range(nv):
        st.insert([v])
    for k, arr in sorted(cells.items()):
        st.insert_batch(np.ascontiguousarray(arr.T), np.zeros(len(arr)))
    build_s = time.perf_counter() - t1
    t2 = time.perf_counter()
    st.compute_persistence(homology_coeff_field=2, persistence_dim_max=True)
    betti = st.betti_numbers()
    hom_s = time.perf_counter() - t2
    print(json.dumps({"peer": "gudhi", "version": gudhi.__version__, "input": path,
                      "num_simplices": st.num_simplices(), "load_s": round(load_s, 3),
                      "build_s": round(build_s, 3), "persistence_betti_s": round(hom_s, 3),
                      "total_s": round(build_s + hom_s, 3), "betti": betti}))


if __name__ == "__main__":
    main()
