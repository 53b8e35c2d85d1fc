#!/bin/bash
# A/B timing of `starplex bench ia-star` on a noisy machine: the binaries run alternately, round
# by round, on the same files, and the median, min and max of each (binary, file) are printed.
#
#   scripts/ab_bench.sh ROUNDS REPS "FILE..." BINARY...
#   e.g. scripts/ab_bench.sh 9 5 "$D/tet_armadillo_m.spx $D/tri_armadillo_x16.off" old/starplex target/release/starplex
#
# REPS is passed to --reps (1 = the first build of a process).
set -euo pipefail
rounds=$1 reps=$2 files=$3
shift 3
for _ in $(seq "$rounds"); do
  for f in $files; do
    for b in "$@"; do
      us=$("$b" bench ia-star "$f" --reps "$reps" --json --quiet |
        python3 -c 'import json,sys; print(json.load(sys.stdin)["us_per_top"])')
      echo "$b $(basename "$f") $us"
    done
  done
done | python3 -c '
import collections, statistics, sys
d = collections.defaultdict(list)
for line in sys.stdin:
    b, f, v = line.split()
    d[(f, b)].append(float(v))
for (f, b), v in sorted(d.items()):
    print(f"{f} {b}: median {statistics.median(v):.4f} min {min(v):.4f} max {max(v):.4f} (n {len(v)})")'
