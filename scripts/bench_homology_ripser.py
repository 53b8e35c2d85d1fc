"""Betti numbers of a Vietoris-Rips complex at one scale with Ripser, for the side-by-side
comparison in BENCHMARKS.md ("Homology"): the points are the vertices of a starplex .spx file,
the edges those of length <= EPS (a sparse distance matrix from a k-d tree), and the Betti
numbers at EPS are the bars Ripser leaves open (born at <= EPS, never dying: the filtration
stops at EPS).

    venv/bin/python scripts/bench_homology_ripser.py FILE.spx EPS [MAXDIM]

Prints one JSON line: load time (not compared), distance-matrix time, Ripser time, Betti
numbers up to MAXDIM (default 2). Wrap with /usr/bin/time for the peak RSS.
"""
import json
import sys
import time

import numpy as np
from ripser import ripser
from scipy.spatial import cKDTree


def read_spx_points(path):
    with open(path) as f:
        lines = [l for l in (x.strip() for x in f) if l and not l.startswith('#')]
    d, nv, _ = map(int, lines[1].split())
    return np.array([list(map(float, l.split()[:d])) for l in lines[2:2 + nv]])


def main():
    path, eps = sys.argv[1], float(sys.argv[2])
    maxdim = int(sys.argv[3]) if len(sys.argv) > 3 else 2
    t0 = time.perf_counter()
    pts = read_spx_points(path)
    load_s = time.perf_counter() - t0
    t1 = time.perf_counter()
    dm = cKDTree(pts).sparse_distance_matrix(cKDTree(pts), eps, output_type='coo_matrix')
    dm_s = time.perf_counter() - t1
    t2 = time.perf_counter()
    r = ripser(dm, distance_matrix=True, maxdim=maxdim)
    ripser_s = time.perf_counter() - t2
    betti = [int(np.sum(np.isinf(d[:, 1]))) for d in r['dgms']]
    print(json.dumps({"peer": "ripser", "input": path, "eps": eps, "n_points": len(pts),
                      "n_edges": int(np.sum(dm.row < dm.col)), "load_s": round(load_s, 3),
                      "distance_matrix_s": round(dm_s, 3), "ripser_s": round(ripser_s, 3),
                      "total_s": round(dm_s + ripser_s, 3), "betti": betti}))


if __name__ == '__main__':
    main()
