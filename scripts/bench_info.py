#!/usr/bin/env python3
"""`starplex info` vs the NumPy ground truth (../shared/peers/prep_data.py info), back to back.

usage: scripts/bench_info.py PYTHON FILE [FILE ...] [--runs N]
PYTHON is a Python with numpy (e.g. the venv made by ../shared/datasets/get). Each FILE is timed
alternately with both tools, N runs each (default 3); prints medians and the ratio.
"""
import os, statistics, subprocess, sys, time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PEERS = os.path.join(ROOT, '..', 'shared', 'peers')
BIN = os.path.join(ROOT, 'target', 'release', 'starplex')

def timed(cmd, cwd=None):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=cwd)
    return time.perf_counter() - t0

def main():
    args = sys.argv[1:]
    runs = 3
    if '--runs' in args:
        i = args.index('--runs'); runs = int(args[i + 1]); del args[i:i + 2]
    py, files = args[0], args[1:]
    print('| input | size MB | NumPy info (s) | starplex info (s) | ratio |')
    print('|---|---|---|---|---|')
    for f in files:
        a, b = [], []
        for _ in range(runs):
            a.append(timed([py, os.path.join(PEERS, 'prep_data.py'), 'info', os.path.abspath(f)], cwd=PEERS))
            b.append(timed([BIN, '--quiet', 'info', f, '--json']))
        ma, mb = statistics.median(a), statistics.median(b)
        print('| %s | %.1f | %.2f | %.3f | %.1fx |' % (os.path.basename(f), os.path.getsize(f) / 1e6, ma, mb, ma / mb))

main()
