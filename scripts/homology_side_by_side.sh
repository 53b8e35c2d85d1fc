#!/bin/bash
# Interleaved side-by-side homology runs, GUDHI and starplex, on tri_armadillo_x16 and
# tet_armadillo_m (whole processes under /usr/bin/time; starplex with 2 and 1 threads):
#
#   DATA=/path/to/medium PY=venv/bin/python scripts/homology_side_by_side.sh ROUNDS BIN... > OUT.txt
#   python3 scripts/homology_side_summary.py OUT.txt
R=${1:-5}; shift
D=${DATA:-/work/data/medium}
PY=${PY:-python3}
HERE=$(cd "$(dirname "$0")" && pwd)
for r in $(seq "$R"); do
 for f in "$D/tri_armadillo_x16/tri_armadillo_x16.spx" "$D/tet_armadillo_m/tet_armadillo_m.spx"; do
  n=$(basename "$f" .spx)
  o=$( { /usr/bin/time -f "WALL %e RSS %M" "$PY" "$HERE/bench_homology_gudhi.py" "$f"; } 2>&1 )
  echo "gudhi $n $(echo "$o" | tr '\n' ' ')"
  for b in "$@"; do for th in 2 1; do
   o=$( { /usr/bin/time -f "WALL %e RSS %M" "$b" homology "$f" --json --quiet --threads $th; } 2>&1 | tr -d ' \n')
   hs=$(echo "$o" | grep -o '"homology_s":[0-9.]*' | cut -d: -f2)
   w=$(echo "$o" | grep -o 'WALL[0-9.]*' | sed 's/WALL//')
   rss=$(echo "$o" | grep -o 'RSS[0-9]*' | sed 's/RSS//')
   echo "sp $(basename "$b") t$th $n homology_s $hs wall $w rss $rss"
  done; done
 done
done
