#!/usr/bin/env python3
"""QEM to 10% side by side, interleaved: per repetition, fast_simplification's call, the meshoptimizer
wrapper's call (both in this process, on the mesh read once) and each starplex binary's `time_s`
(`simplify IN OUT --mode qem --ratio 0.1 --threads 1 --no-report --json`: the simplification alone,
no file I/O). Prints each tool's times and median, and the ratios per repetition (the machine is
shared: ratios from one repetition are the fair comparison).

    $DATA/.venv/bin/python scripts/bench_qem_peers.py MESH.off STARPLEX_INPUT REPS BIN [BIN ...]

STARPLEX_INPUT is the same mesh in a fast format (e.g. `starplex convert MESH.off x.spb`). Needs
fast_simplification and meshoptimizer in the venv and ../shared/peers (tda_common.load_any).
"""
import json, os, subprocess, sys, tempfile, time
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "peers"))
from tda_common import load_any
import fast_simplification
import meshoptimizer as mo

mesh, inp, reps, bins = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
d = load_any(mesh)
V, F = np.asarray(d["V"], dtype=np.float64), np.asarray(d["F"], dtype=np.int64)
target = len(F) // 10
out = os.path.join(tempfile.mkdtemp(), "out.spb")
res = {"fast_simplification": [], "meshoptimizer": []} | {b: [] for b in bins}
for _ in range(reps):
    t = time.perf_counter()
    fast_simplification.simplify(V, F, target_reduction=0.9)
    res["fast_simplification"].append(time.perf_counter() - t)
    idx = F.reshape(-1).astype(np.uint32)
    dest, V32 = np.zeros_like(idx), V.astype(np.float32)
    t = time.perf_counter()
    mo.simplify(dest, idx, V32, target_index_count=target * 3, target_error=1.0)
    res["meshoptimizer"].append(time.perf_counter() - t)
    for b in bins:
        o = subprocess.run([b, "simplify", inp, out, "--mode", "qem", "--ratio", "0.1", "--threads", "1",
                            "--no-report", "--json", "--quiet"], capture_output=True, text=True, check=True)
        res[b].append(json.loads(o.stdout)["time_s"])
med = lambda v: sorted(v)[len(v) // 2]
for k, v in res.items():
    print(f"{k:24s} {' '.join('%.3f' % x for x in v)}  median {med(v):.3f}")
for b in bins:
    fs = [f / s for f, s in zip(res["fast_simplification"], res[b])]
    mo_ = [s / m for s, m in zip(res[b], res["meshoptimizer"])]
    print(f"{b}: fast_simplification / starplex per rep {' '.join('%.2f' % x for x in fs)} (median {med(fs):.2f}); "
          f"starplex / meshoptimizer {' '.join('%.2f' % x for x in mo_)} (median {med(mo_):.2f})")
