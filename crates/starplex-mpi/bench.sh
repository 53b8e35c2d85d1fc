#!/bin/sh
# Memory per rank, ghost share, bytes sent and time of starplex-mpi against the single process.
#   crates/starplex-mpi/bench.sh FILE [RANKS...]     (default ranks: 1 2 4; release build first:
#   cargo build --release -p starplex-cli -p starplex-mpi)
# Prints, per verb: the single process (2 threads) wall time and peak RSS, then for each P the
# wall time of mpirun and one line per rank (--stats: owned/held vertices and cells, ghost share
# = held cells not owned / held cells, bytes sent to other ranks, peak RSS in KiB).
set -eu
f="$1"; shift
ranks="${*:-1 2 4}"
cd "$(dirname "$0")/../.."
bin=target/release
tmp="${TMPDIR:-/tmp}/starplex-mpi-bench-$$"
mkdir -p "$tmp"
spb="$tmp/$(basename "${f%.*}").spb"
"$bin/starplex" --quiet convert "$f" "$spb"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for verb in info validate; do
    extra=""
    [ "$verb" = validate ] && extra="--threads 2"
    echo "== $verb, single process (2 threads)"
    RAYON_NUM_THREADS=2 /usr/bin/time -f "wall %e s, peak RSS %M KiB" \
        "$bin/starplex" --quiet "$verb" "$spb" --json $extra > "$tmp/one.json"
    for p in $ranks; do
        echo "== $verb, mpirun -np $p"
        /usr/bin/time -f "wall %e s (mpirun)" mpirun --allow-run-as-root --oversubscribe -np "$p" \
            "$bin/starplex-mpi" "$verb" "$spb" --json --stats > "$tmp/p.json"
        python3 - "$tmp/one.json" "$tmp/p.json" <<'PY'
import json, sys
a, b = (json.load(open(x)) for x in sys.argv[1:])
for v in (a, b):
    v.pop("timings", None)
print("   output equals the single process:", a == b)
PY
    done
done
rm -rf "$tmp"
