#!/usr/bin/env python3
"""Compare `starplex info --json` with the third-party oracles on every dataset found.

usage: scripts/check_oracles.py DATA_DIR [SIZE ...]   (DATA_DIR as made by ../shared/datasets/get;
SIZE defaults to small medium). Prints one line per dataset and exits 1 on any mismatch.
"""
import json, os, subprocess, sys, time

from datasets import BIN, with_oracles
FIELDS = ['n_vertices', 'n_isolated_vertices', 'ambient_dim', 'dim', 'pure', 'top_cells', 'n_top_cells',
          'f_vector', 'euler_characteristic', 'n_boundary_faces', 'n_faces_shared_by_more_than_2_top_cells',
          'n_connected_components', 'faces_by_type']

def main():
    data = sys.argv[1]
    sizes = sys.argv[2:] or ['small', 'medium']
    bad = 0
    for size, name, spx, o in with_oracles(data, sizes):
        t0 = time.time()
        out = subprocess.run([BIN, '--quiet', 'info', spx, '--json'], capture_output=True, text=True)
        wall = time.time() - t0
        if out.returncode != 0:
            print('%-20s FAILED: %s' % (name, out.stderr.strip()))
            bad += 1
            continue
        a = json.loads(out.stdout)
        diffs = [(k, a.get(k), o[k]) for k in FIELDS if k in o and o[k] is not None and a.get(k) != o[k]]
        for i, (lo, hi) in enumerate(zip(*o['bbox'])):
            if abs(a['bbox'][0][i] - lo) > 1e-9 or abs(a['bbox'][1][i] - hi) > 1e-9:
                diffs.append(('bbox', a['bbox'], o['bbox']))
                break
        bad += bool(diffs)
        mb = os.path.getsize(spx) / 1e6
        print('%-20s %-8s %7.1f MB  read %.2fs  info %.2fs  wall %.2fs  %s' % (
            name, size, mb, a['timings']['read_s'], a['timings']['info_s'], wall,
            'OK' if not diffs else 'MISMATCH %s' % diffs))
    sys.exit(1 if bad else 0)

main()
