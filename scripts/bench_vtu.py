#!/usr/bin/env python3
"""Load speed of VTK XML `.vtu`: starplex against meshio and VTK's own reader, same files, same run.

    starplex generate grid 100 100 100 -o /tmp/g100.spb && starplex convert /tmp/g100.spb /tmp/g100.vtu
    python scripts/bench_vtu.py target/release/starplex /tmp/g100.vtu [more.vtu ...]

(a venv with `pip install meshio vtk numpy`). Best of 2 warm runs each. starplex's time is
`info --json`'s `timings.read_s` (parse + checked build of the complex), meshio's `meshio.read`,
VTK's `vtkXMLUnstructuredGridReader.Update()` (parse only, no checks).
"""
import json
import os
import subprocess
import sys
import time


def best(f, n=2):
    return min(f() for _ in range(n))


def starplex(exe, path):
    out = subprocess.run([exe, "info", "--json", "--max-faces", "1", "--quiet", path],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["timings"]["read_s"]


def timed(f):
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


def main():
    exe, files = sys.argv[1], sys.argv[2:]
    import meshio
    import vtk

    def vtk_read(p):
        r = vtk.vtkXMLUnstructuredGridReader()
        r.SetFileName(p)
        r.Update()

    print("| file | MB | starplex s | MB/s | meshio s | meshio / starplex | VTK s | VTK / starplex |")
    print("|---|---|---|---|---|---|---|---|")
    for p in files:
        mb = os.path.getsize(p) / 1e6
        s = best(lambda: starplex(exe, p))
        m = best(lambda: timed(lambda: meshio.read(p)))
        v = best(lambda: timed(lambda: vtk_read(p)))
        print("| %s | %.0f | %.2f | %.0f | %.2f | %.2f | %.2f | %.2f |"
              % (os.path.basename(p), mb, s, mb / s, m, m / s, v, v / s), flush=True)


if __name__ == "__main__":
    main()
