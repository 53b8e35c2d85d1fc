#!/usr/bin/env python3
"""CPU-time comparison, 3 alternating reps: fast_simplification's library call (process_time)
vs each starplex binary's whole process (user+sys of `simplify MESH OUT --ratio 0.1 --no-report
--threads 1`, reading and writing included).

    python scripts/bench_simplify_cpu.py MESH.spx STARPLEX_BIN [STARPLEX_BIN ...]

Needs the peers' venv (fast_simplification) and ../shared/peers (tda_common.load_any).
"""
import os, subprocess, sys, tempfile, time, resource
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "peers"))
from tda_common import load_any
import fast_simplification
mesh, bins = sys.argv[1], sys.argv[2:]
out = os.path.join(tempfile.mkdtemp(), "out.spx")
d = load_any(mesh); V = d["V"].astype(np.float32); F = np.asarray(d["F"], dtype=np.int32)
def fs():
    t = time.process_time(); fast_simplification.simplify(V, F, target_reduction=0.9); return time.process_time() - t
def sp(b):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([b, "simplify", mesh, out, "--ratio", "0.1", "--no-report", "--threads", "1"], check=True, stdout=subprocess.DEVNULL)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
res = {"fast_simplification": []} | {os.path.basename(b): [] for b in bins}
for _ in range(3):
    res["fast_simplification"].append(fs())
    for b in bins:
        res[os.path.basename(b)].append(sp(b))
for k, v in res.items():
    print(k, "cpu s:", [round(x, 2) for x in v], "median", round(sorted(v)[1], 2))
