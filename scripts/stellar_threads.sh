#!/usr/bin/env bash
# One thread against two: `starplex stellar FILE --bench` on each FILE:KV, alternating 1 and 2
# threads, N runs each (default 3); prints one line of phase timings (seconds) per run.
#   SP=target/release/starplex N=3 scripts/stellar_threads.sh tri_armadillo_x16.tri:100 tet_armadillo_m.ts:400
set -euo pipefail
SP=${SP:-target/release/starplex}
N=${N:-3}
[ $# -gt 0 ] || { echo "usage: scripts/stellar_threads.sh FILE:KV..." >&2; exit 2; }
for f in "$@"; do
  p=${f%%:*}; kv=${f##*:}
  for r in $(seq "$N"); do
    for th in 1 2; do
      printf '%s th=%s rep=%s ' "$(basename "$p")" "$th" "$r"
      "$SP" stellar "$p" --kv "$kv" --threads "$th" --json --quiet --bench | python3 -c '
import json, sys
d = json.load(sys.stdin)
def find(o, k):
    if isinstance(o, dict):
        if k in o:
            return o[k]
        for v in o.values():
            r = find(v, k)
            if r is not None:
                return r
    return None
keys = ["build_s", "vt_local_s", "vt_all_s", "p_faces_s", "iastar_global_s", "validate_s"]
print(" ".join("%s=%.4f" % (k, find(d, k) or -1) for k in keys))'
    done
  done
done
