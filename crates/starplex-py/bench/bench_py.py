"""Python-side benchmarks of starplex on one mesh, peers in the same run.

    python bench_py.py MESH.spx [--cli target/release/starplex] [--repeat 3]

Needs starplex importable, and gudhi / trimesh for the peer columns (skipped when missing).
Prints one JSON object per measurement; the best of --repeat runs is reported.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import time

import numpy as np

import starplex


def best(f, repeat):
    ts = []
    out = None
    for _ in range(repeat):
        t = time.perf_counter()
        out = f()
        ts.append(time.perf_counter() - t)
    return min(ts), out


def rss_mb():
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


# anonymous resident memory a Complex adds, from two .npy files: "shared" reads them as
# read-only memory maps, "copy" as ordinary arrays
CHILD = """
import json, sys, numpy as np, starplex
def anon():
    for line in open("/proc/self/status"):
        if line.startswith("RssAnon:"):
            return int(line.split()[1]) / 1024
p = np.load(sys.argv[1], mmap_mode="r")
t = np.load(sys.argv[2], mmap_mode="r")
if sys.argv[3] == "copy":
    p, t = np.array(p), np.array(t)
r0 = anon()
c = starplex.Complex(p, t)
print(json.dumps({"grew_mb": anon() - r0}))
"""


def emit(**kw):
    print(json.dumps(kw), flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("--cli", default=None)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    name = os.path.basename(a.mesh)

    t_read, c = best(lambda: starplex.read(a.mesh), 1)
    pts = np.array(c.points)  # writeable float64 (c.points is a read-only view, shared)
    cells = c.cells.astype(np.int64)  # what numpy users usually hold
    k = cells.shape[1]
    emit(bench="read", mesh=name, s=t_read, n_vertices=c.n_vertices, n_cells=c.n_cells)

    # 1. building from the same arrays
    t_cx, c2 = best(lambda: starplex.Complex(pts, cells), a.repeat)
    t_st, _ = best(lambda: starplex.SimplexTree(starplex.Complex(pts, cells)), a.repeat)
    t_ia, _ = best(lambda: starplex.IaStar(starplex.Complex(pts, cells)), a.repeat)
    row = dict(bench="build_from_numpy", mesh=name, starplex_complex_s=t_cx,
               starplex_complex_plus_simplex_tree_s=t_st, starplex_complex_plus_iastar_s=t_ia)
    try:
        import gudhi

        cells_t = np.ascontiguousarray(cells.T)
        filt = np.zeros(len(cells))

        def gudhi_build():
            st = gudhi.SimplexTree()
            st.insert_batch(cells_t, filt)
            return st

        t_g, st = best(gudhi_build, a.repeat)
        row.update(gudhi_insert_batch_s=t_g, gudhi_num_simplices=st.num_simplices(),
                   ratio_gudhi_over_complex=t_g / t_cx, ratio_gudhi_over_simplex_tree=t_g / t_st,
                   ratio_gudhi_over_iastar=t_g / t_ia)
    except ImportError:
        row.update(gudhi="not installed")
    emit(**row)

    # 1b. the same arrays as read-only memory maps (float64 points, uint32 cells): shared, not
    # copied; anonymous resident memory of the complex against the copying build
    tmp = os.path.join("/tmp", f"bench-py-{os.getpid()}")
    os.makedirs(tmp, exist_ok=True)
    np.save(os.path.join(tmp, "p.npy"), pts)
    np.save(os.path.join(tmp, "t.npy"), cells.astype(np.uint32))
    mp = np.load(os.path.join(tmp, "p.npy"), mmap_mode="r")
    mt = np.load(os.path.join(tmp, "t.npy"), mmap_mode="r")
    t_sh, c3 = best(lambda: starplex.Complex(mp, mt), a.repeat)
    shared = bool(np.shares_memory(c3.points, mp) and np.shares_memory(c3.cells, mt))
    del c2, c3
    growth = {}  # measured in a fresh child process each: this one has freed memory to reuse
    for what in ["copy", "shared"]:
        out = subprocess.run([sys.executable, "-c", CHILD, os.path.join(tmp, "p.npy"),
                              os.path.join(tmp, "t.npy"), what],
                             capture_output=True, text=True, check=True)
        growth[what] = json.loads(out.stdout)["grew_mb"]
    emit(bench="build_from_memory_maps", mesh=name, starplex_complex_shared_s=t_sh,
         starplex_complex_copied_s=t_cx, shares_memory=shared,
         arrays_mb=(pts.nbytes + len(cells) * k * 4) / 2**20,
         anon_growth_copied_mb=growth["copy"], anon_growth_shared_mb=growth["shared"])
    del mp, mt
    for f in ["p.npy", "t.npy"]:
        os.remove(os.path.join(tmp, f))
    os.rmdir(tmp)

    # 2. VT of every vertex as CSR vs trimesh's vertex_faces
    s = starplex.IaStar(c)
    t_vt, (off, vals) = best(lambda: s.vt(), a.repeat)
    row = dict(bench="vt_all", mesh=name, starplex_iastar_vt_s=t_vt, n_values=int(len(vals)))
    t_cvt, (coff, cvals) = best(lambda: c.vt(), a.repeat)
    assert np.array_equal(coff, off) and np.array_equal(cvals, vals)
    row.update(starplex_complex_vt_s=t_cvt)
    t_vt_tree, _ = best(lambda: starplex.StellarTree(c).vt(), a.repeat)
    row.update(starplex_build_stellar_plus_vt_s=t_vt_tree)
    if k == 3:
        try:
            import trimesh

            def tm():
                m = trimesh.Trimesh(vertices=pts, faces=cells, process=False)
                return m.vertex_faces

            t_tm, vf = best(tm, a.repeat)
            # the same answer: trimesh pads rows with -1
            ok = all(
                sorted(vf[v][vf[v] >= 0].tolist()) == vals[off[v]:off[v + 1]].tolist()
                for v in range(0, c.n_vertices, max(1, c.n_vertices // 1000))
            )
            row.update(trimesh_vertex_faces_s=t_tm, ratio_trimesh_over_iastar_vt=t_tm / t_vt,
                       ratio_trimesh_over_complex_vt=t_tm / t_cvt,
                       same_answers_sampled=ok)
        except ImportError:
            row.update(trimesh="not installed")
    emit(**row)

    # arrays are handed to NumPy without a copy: resident memory grows by the answer, once
    del off, vals
    r0 = rss_mb()
    off, vals = s.vt()
    r1 = rss_mb()
    emit(bench="vt_all_memory", mesh=name, answer_mb=(off.nbytes + vals.nbytes) / 2**20,
         rss_growth_mb=r1 - r0, values_base=type(vals.base).__name__,
         values_owndata=bool(vals.flags["OWNDATA"]))

    # 3. Python overhead: the same work as one command-line run (read, IA*, VT of every vertex)
    if a.cli:
        def py_all():
            cc = starplex.read(a.mesh)
            return starplex.IaStar(cc).vt()

        t_py, _ = best(py_all, a.repeat)
        out = os.path.join("/tmp", f"bench-py-{os.getpid()}.npz")

        def cli_all():
            subprocess.run([a.cli, "--quiet", "query", a.mesh, "--structure", "ia-star", "--relation",
                            "vt", "--all", "--threads", str(os.cpu_count()), "--out", out], check=True)

        t_cli, _ = best(cli_all, a.repeat)
        t_py_npz, _ = best(lambda: np.savez(out, *py_all()), a.repeat)
        os.remove(out)
        emit(bench="python_vs_cli", mesh=name, python_read_iastar_vt_s=t_py,
             cli_query_all_out_npz_s=t_cli, python_same_plus_savez_s=t_py_npz,
             overhead_vs_cli=t_py_npz / t_cli - 1.0)


if __name__ == "__main__":
    main()
