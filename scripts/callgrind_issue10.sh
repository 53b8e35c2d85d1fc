#!/bin/sh
# usage: run_cg.sh BIN TAG ; instruction counts of the issue-10 benchmarks (1 thread)
B=$1; T=$2; D=/work/data/small
cg() { name=$1; shift; valgrind --tool=callgrind --callgrind-out-file=/work/cg/$T.$name.out "$@" >/dev/null 2>/work/cg/$T.$name.err; grep -o "Collected : [0-9]*" /work/cg/$T.$name.err | awk -v n=$name -v t=$T '{print t, n, $3}'; }
cg stellar_tet $B stellar $D/tet_elephant/tet_elephant.spx --threads 1 --bench --json --quiet
cg stellar_tri $B stellar $D/tri_elephant/tri_elephant.spx --threads 1 --bench --json --quiet
cg iastar_tet $B bench ia-star $D/tet_elephant/tet_elephant.spx --quiet
cg st_tet $B bench simplex-tree $D/tet_elephant/tet_elephant.spx --quiet
cg hasse_tri $B bench hasse $D/tri_elephant/tri_elephant.spx --quiet
