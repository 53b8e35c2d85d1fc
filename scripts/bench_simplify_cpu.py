# CPU-time comparison: fast_simplification's call (process_time) vs the starplex process
# (user+sys of `simplify --no-report --threads 1`, reading and writing included), alternating.
import os, subprocess, sys, time, resource
import numpy as np
sys.path.insert(0, "/work/shared/peers")
from tda_common import load_any
import fast_simplification
mesh, bins = sys.argv[1], sys.argv[2:]
d = load_any(mesh); V = d["V"].astype(np.float32); F = np.asarray(d["F"], dtype=np.int32)
def fs():
    t = time.process_time(); fast_simplification.simplify(V, F, target_reduction=0.9); return time.process_time() - t
def sp(b):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([b, "simplify", mesh, "/tmp/h/cpu_out.spx", "--ratio", "0.1", "--no-report", "--threads", "1"], check=True, stdout=subprocess.DEVNULL)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
res = {"fast_simplification": []} | {os.path.basename(b): [] for b in bins}
for _ in range(3):
    res["fast_simplification"].append(fs())
    for b in bins:
        res[os.path.basename(b)].append(sp(b))
for k, v in res.items():
    print(k, "cpu s:", [round(x, 2) for x in v], "median", round(sorted(v)[1], 2))
