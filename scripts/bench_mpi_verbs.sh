#!/bin/bash
# Wall time and peak memory of every distributed verb against the single process, on one .spb:
# `starplex VERB` (its default threads) and `mpirun -np P starplex-mpi VERB --stats` for P = 2, 4
# (peak resident memory of each rank from --stats, KiB). Issue 17's memory bound: per rank
# <= (1/P + ghost share) x the single process's peak + a constant.
#   scripts/bench_mpi_verbs.sh FILE.spb [BIN_DIR]      (BIN_DIR: target/release)
set -u
F=$1
B=${2:-target/release}
T=$(mktemp -d)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
MPI="mpirun -q --allow-run-as-root --oversubscribe -x OMPI_MCA_btl_vader_single_copy_mechanism=none"
one() { # name, single-process arguments, starplex-mpi arguments
  /usr/bin/time -f "%e %M" -o "$T/t" "$B/starplex" --quiet $2 > /dev/null 2> "$T/e" || cat "$T/e"
  echo "$1 single: $(tail -1 "$T/t") (s, peak KiB)"
  for p in 2 4; do
    /usr/bin/time -f "%e" -o "$T/t" $MPI -np $p "$B/starplex-mpi" $3 --stats > /dev/null 2> "$T/e" || cat "$T/e"
    echo "$1 P=$p: $(tail -1 "$T/t") s, peak KiB per rank: $(grep -E '^[0-9]+ ' "$T/e" | awk '{print $NF}' | tr '\n' ' ')"
  done
  rm -f "$T"/out.*
}
one info "info $F" "info $F"
one validate "validate $F" "validate $F"
one homology "homology $F" "homology $F"
one simplify "simplify $F $T/out.spb --mode homology --no-report" "simplify $F -o $T/out.spb --mode homology --no-report"
one query "query $F --structure stellar --relation vt --all --out $T/out.jsonl" "query $F --relation vt --all --out $T/out.jsonl"
rm -rf "$T"
