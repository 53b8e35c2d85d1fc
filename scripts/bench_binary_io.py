#!/usr/bin/env python3
"""Load speed of binary gmsh / legacy VTK: starplex against meshio, same files, same run.

    scripts/make_io_corpus.py --big 100 /tmp/g100.msh /tmp/g100.vtk   # 6M tets, 1M points
    scripts/bench_binary_io.py target/release/starplex /tmp/g100.msh /tmp/g100.vtk

Best of 3 warm runs each (the first run of each file also warms the page cache). starplex's
time is `info --json`'s `timings.read_s` (parse + checked build of the complex: index range,
repeated vertices, duplicate and face cells), meshio's is `meshio.read` (parse only).
"""
import json
import os
import subprocess
import sys
import time

import meshio


def starplex_read(exe, path):
    out = subprocess.run([exe, "info", "--json", "--max-faces", "1", "--quiet", path],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["timings"]["read_s"]


def meshio_read(path):
    t = time.perf_counter()
    meshio.read(path)
    return time.perf_counter() - t


def main():
    exe = sys.argv[1]
    print("| file | size MB | starplex s | starplex MB/s | meshio s | meshio MB/s | meshio / starplex |")
    print("|---|---|---|---|---|---|---|")
    for path in sys.argv[2:]:
        mb = os.path.getsize(path) / 1e6
        starplex_read(exe, path)  # warm the page cache
        s = min(starplex_read(exe, path) for _ in range(3))
        m = min(meshio_read(path) for _ in range(3))
        print(f"| {os.path.basename(path)} | {mb:.0f} | {s:.3f} | {mb / s:.0f} | {m:.3f} | {mb / m:.0f} | {m / s:.2f} |")


if __name__ == "__main__":
    main()
