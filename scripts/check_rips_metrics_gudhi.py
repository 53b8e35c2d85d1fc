"""Compare `starplex rips --metric M` with GUDHI's RipsComplex(distance_matrix=...) on small
random point clouds: the number of simplices per dimension (starplex's maximal simplices
expanded to all faces). Usage: python check_rips_metrics_gudhi.py STARPLEX_BIN"""
import itertools, json, os, subprocess, sys, tempfile
import numpy as np, gudhi
from scipy.spatial.distance import cdist

exe = sys.argv[1]
rng = np.random.default_rng(14)
tmp = tempfile.mkdtemp()
ok = 0
for trial in range(24):
    n, dim = int(rng.integers(8, 30)), int(rng.integers(2, 10))
    pts = rng.integers(0, 5, size=(n, dim)).astype(float) if trial % 2 else rng.random((n, dim))
    for metric, sp in [("euclidean", "euclidean"), ("manhattan", "cityblock"), ("chebyshev", "chebyshev")]:
        D = cdist(pts, pts, sp)
        eps = float(np.quantile(D[D > 0], 0.25))
        if metric == "euclidean":
            # starplex decides L2 by the squared test (scipy's), GUDHI compares sqrt: ties at
            # exactly eps may differ by one rounding, so use a scale between two distances.
            # L1 and L-inf keep exact ties (integer grids on odd trials).
            u = np.unique(D)
            i = np.searchsorted(u, eps)
            eps = float((u[i] + u[i + 1]) / 2)
        for inp, m in [("points", metric), ("matrix", "precomputed")]:
            f = os.path.join(tmp, "p.txt" if inp == "points" else "d.npy")
            np.savetxt(f, pts) if inp == "points" else np.save(f, D)
            out = os.path.join(tmp, "o.spx")
            r = subprocess.run([exe, "--quiet", "rips", f, "--eps", repr(eps), "--metric", m, "-o", out],
                               capture_output=True, text=True)
            assert r.returncode == 0, r.stderr
            j = json.loads(subprocess.run([exe, "--quiet", "info", out, "--json"], capture_output=True, text=True).stdout)
            st = gudhi.RipsComplex(distance_matrix=D, max_edge_length=eps).create_simplex_tree(max_dimension=n)
            g = {}
            for s, _ in st.get_simplices():
                g[len(s) - 1] = g.get(len(s) - 1, 0) + 1
            mine = {d: c for d, c in enumerate(j["f_vector"]) if c}
            assert mine == g, (trial, metric, inp, mine, g)
            ok += 1
print(f"{ok} runs: simplex counts per dimension equal GUDHI's")
