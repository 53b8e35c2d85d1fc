"""pyvista's off-screen screenshot of a triangle OFF mesh, timed like `starplex render`
(BENCHMARKS.md, "Pictures"). Usage: python render_pyvista_bench.py MESH.off OUT.png
Needs pyvista + vtk (a venv that sees /work/data/vtkvenv: see BENCHMARKS.md)."""
import sys
import time

import numpy as np
import pyvista as pv

path = sys.argv[1]
t0 = time.perf_counter()
lines = open(path).read().split("\n")
nv, nf, _ = map(int, lines[1].split())
V = np.array([l.split() for l in lines[2 : 2 + nv]], dtype=float)
F = np.array([l.split() for l in lines[2 + nv : 2 + nv + nf]], dtype=np.int64)
mesh = pv.PolyData(V, F.ravel())
t1 = time.perf_counter()
print(f"load {t1-t0:.2f} s, {mesh.n_cells} cells (not timed below)", flush=True)
pl = pv.Plotter(off_screen=True, window_size=(1600, 1200))
pl.add_mesh(mesh, color="lightsteelblue")
pl.view_isometric()
t2 = time.perf_counter()
c2 = time.process_time()
pl.screenshot(sys.argv[2])
t3 = time.perf_counter()
c3 = time.process_time()
print(f"setup {t2-t1:.3f} s; first screenshot {t3-t2:.3f} s, cpu {c3-c2:.3f} s (GL context + upload + draw + PNG)")
for _ in range(2):
    pl.camera.azimuth += 10
    t4, c4 = time.perf_counter(), time.process_time()
    pl.screenshot(sys.argv[2])
    t5, c5 = time.perf_counter(), time.process_time()
    print(f"re-render {t5-t4:.3f} s, cpu {c5-c4:.3f} s")
pl.close()
