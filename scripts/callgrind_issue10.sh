#!/bin/sh
# Whole-run instruction counts of the issue-10 benchmarks (one thread), for comparing two builds:
#   scripts/callgrind_issue10.sh path/to/starplex TAG
# prints "TAG run instructions" per run. Data: $STARPLEX_DATA/small (default /work/data/small);
# callgrind files go to $CG_OUT (default /tmp/cg).
B=$1; T=$2; D=${STARPLEX_DATA:-/work/data}/small; O=${CG_OUT:-/tmp/cg}
mkdir -p "$O"
cg() { name=$1; shift; valgrind --tool=callgrind --callgrind-out-file="$O/$T.$name.out" "$@" >/dev/null 2>"$O/$T.$name.err"; grep -o "Collected : [0-9]*" "$O/$T.$name.err" | awk -v n=$name -v t=$T '{print t, n, $3}'; }
cg stellar_tet "$B" stellar $D/tet_elephant/tet_elephant.spx --threads 1 --bench --json --quiet
cg stellar_tri "$B" stellar $D/tri_elephant/tri_elephant.spx --threads 1 --bench --json --quiet
cg iastar_tet "$B" bench ia-star $D/tet_elephant/tet_elephant.spx --quiet
cg st_tet "$B" bench simplex-tree $D/tet_elephant/tet_elephant.spx --quiet
cg hasse_tri "$B" bench hasse $D/tri_elephant/tri_elephant.spx --quiet
