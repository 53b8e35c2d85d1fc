#!/usr/bin/env python3
"""QEM decimation side by side, one run: starplex against fast_simplification and PyMeshLab's
quadric edge collapse on the same mesh and target, with wall time, CPU time and peak memory.

    python scripts/bench_simplify_side.py STARPLEX_BIN MESH.spx [MESH.spx ...] [--ratio 0.1] [--reps 3]

(with the peers' venv python: fast-simplification, pymeshlab). Each tool runs in its own child
process, the tools alternate within each repetition, and medians are reported.

* starplex: `BIN simplify MESH OUT --ratio R --no-report --threads 1 --json`, the whole process:
  wall and CPU (user + sys) include reading the .spx and writing the result; `time_s` is the
  simplification alone (building the working structure, contracting, writing it back). Peak
  RSS is the process's (wait4), and "input" is the peak RSS of `BIN info MESH` (the loaded
  mesh alone), so peak / input is the memory the issue bounds.
* peers: the child loads the mesh, then times the library call alone (wall: perf_counter, CPU:
  process_time) and reports the peak RSS during the call minus the RSS before it ("delta"),
  and the child's whole peak.

Prints one JSON line per (tool, rep), then a markdown table of medians and ratios
(peer ÷ starplex: above 1, starplex is faster / smaller).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PEERS = os.path.join(HERE, "..", "..", "shared", "peers")

CHILD = r"""
import json, resource, sys, time
sys.path.insert(0, PEERS)
import numpy as np
from tda_common import load_any
name, mesh, ratio = sys.argv[1], sys.argv[2], float(sys.argv[3])
d = load_any(mesh)
V = np.ascontiguousarray(d["V"], dtype=np.float64)
F = np.ascontiguousarray(d["F"], dtype=np.int32)
target = max(4, int(len(F) * ratio))
def rss_mb():
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
if name == "fast_simplification":
    import fast_simplification
    V32 = V.astype(np.float32)
    before = rss_mb()
    w, c = time.perf_counter(), time.process_time()
    v, f = fast_simplification.simplify(V32, F, target_reduction=1 - ratio)
    wall, cpu = time.perf_counter() - w, time.process_time() - c
    faces = len(f)
elif name == "pymeshlab":
    import pymeshlab as pm
    ms = pm.MeshSet()
    ms.add_mesh(pm.Mesh(V, F))
    before = rss_mb()
    w, c = time.perf_counter(), time.process_time()
    ms.meshing_decimation_quadric_edge_collapse(targetfacenum=target)
    wall, cpu = time.perf_counter() - w, time.process_time() - c
    faces = ms.current_mesh().face_number()
else:
    raise SystemExit(f"unknown peer {name}")
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(json.dumps(dict(wall=wall, cpu=cpu, peak_mb=peak, delta_mb=peak - before, faces=int(faces))))
"""


def run_peer(name, mesh, ratio):
    p = subprocess.run([sys.executable, "-c", CHILD.replace("PEERS", repr(PEERS)), name, mesh, str(ratio)],
                       capture_output=True, text=True, check=True)
    return json.loads(p.stdout.strip().splitlines()[-1])


def run_process(cmd):
    """(wall, cpu, peak MB, stdout) of a child process."""
    t = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    out = p.stdout.read()
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{cmd}: exit {status}")
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024, out


def run_starplex(binary, mesh, ratio, out):
    wall, cpu, peak, stdout = run_process(
        [binary, "simplify", mesh, out, "--ratio", str(ratio), "--no-report", "--threads", "1", "--json"])
    rep = json.loads(stdout)
    return dict(wall=wall, cpu=cpu, peak_mb=peak, time_s=rep.get("time_s"), faces=rep["cells"][1])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("starplex")
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--ratio", type=float, default=0.1)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--peers", nargs="*", default=["fast_simplification", "pymeshlab"])
    a = ap.parse_args()
    tmp = tempfile.mkdtemp()
    table = []
    for mesh in a.meshes:
        _, _, input_mb, _ = run_process([a.starplex, "info", mesh])
        res = {name: [] for name in ["starplex"] + a.peers}
        for rep in range(a.reps):
            order = ["starplex"] + a.peers
            if rep % 2:
                order.reverse()
            for name in order:
                if name == "starplex":
                    r = run_starplex(a.starplex, mesh, a.ratio, os.path.join(tmp, "out.spx"))
                    r["input_mb"] = input_mb
                else:
                    r = run_peer(name, mesh, a.ratio)
                r.update(tool=name, mesh=os.path.basename(mesh), rep=rep)
                print(json.dumps(r), flush=True)
                res[name].append(r)
        med = {n: {k: statistics.median(x[k] for x in rs) for k in ("wall", "cpu", "peak_mb")}
               for n, rs in res.items() if rs}
        sp = med["starplex"]
        sp["time_s"] = statistics.median(x["time_s"] for x in res["starplex"])
        for n in a.peers:
            med[n]["delta_mb"] = statistics.median(x["delta_mb"] for x in res[n])
        table.append((os.path.basename(mesh), input_mb, med))
    print(f"\n| mesh | tool | wall s | CPU s | peak RSS MB | memory measure | wall ratio | CPU ratio |")
    print("|---|---|---:|---:|---:|---|---:|---:|")
    for mesh, input_mb, med in table:
        sp = med["starplex"]
        print(f"| {mesh} | starplex (whole process; simplify alone {sp['time_s']:.3f} s) | {sp['wall']:.3f} | "
              f"{sp['cpu']:.3f} | {sp['peak_mb']:.0f} | {sp['peak_mb'] / input_mb:.2f}x the loaded input "
              f"({input_mb:.0f} MB, `info`) | 1 | 1 |")
        for n, m in med.items():
            if n == "starplex":
                continue
            print(f"| {mesh} | {n} (library call) | {m['wall']:.3f} | {m['cpu']:.3f} | {m['peak_mb']:.0f} | "
                  f"+{m['delta_mb']:.0f} MB during the call | {m['wall'] / sp['wall']:.2f} | "
                  f"{m['cpu'] / sp['cpu']:.2f} |")


if __name__ == "__main__":
    main()
