#!/bin/sh
# Memory per rank, ghost share, bytes sent and time of starplex-mpi against the single process.
#   crates/starplex-mpi/bench.sh FILE [RANKS...]     (default ranks: 1 2 4; release build first:
#   cargo build --release -p starplex-cli -p starplex-mpi)
#   VERBS="info validate homology simplify query" to choose the verbs (default: all five).
# Prints, per verb: the single process (2 threads) wall time and peak RSS, then for each P the
# wall time of mpirun and one line per rank (--stats: owned/held vertices and cells, ghost share
# = held cells not owned / held cells, bytes sent to other ranks, peak RSS in KiB). info and
# validate outputs are compared whole with the single process's, homology by its Betti numbers,
# query by the bytes of the merged file; simplify prints its counts (the result depends on P).
set -eu
f="$1"; shift
ranks="${*:-1 2 4}"
verbs="${VERBS:-info validate homology simplify query}"
cd "$(dirname "$0")/../.."
bin=target/release
tmp="${TMPDIR:-/tmp}/starplex-mpi-bench-$$"
mkdir -p "$tmp"
spb="$tmp/$(basename "${f%.*}").spb"
"$bin/starplex" --quiet convert "$f" "$spb"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for verb in $verbs; do
    case "$verb" in
        validate) one="validate $spb --json --threads 2"; many="validate $spb --json" ;;
        simplify) one="simplify $spb $tmp/one.out.spb --mode homology --no-report --json --threads 2"
                  many="simplify $spb -o $tmp/p.out.spb --mode homology --json" ;;
        query) one="query $spb --structure stellar --relation vt --all --out $tmp/one.jsonl"
               many="query $spb --relation vt --all --out $tmp/p.jsonl" ;;
        *) one="$verb $spb --json"; many="$verb $spb --json" ;;
    esac
    echo "== $verb, single process (2 threads)"
    # shellcheck disable=SC2086
    RAYON_NUM_THREADS=2 /usr/bin/time -f "wall %e s, peak RSS %M KiB" \
        "$bin/starplex" --quiet $one > "$tmp/one.json"
    for p in $ranks; do
        echo "== $verb, mpirun -np $p"
        # shellcheck disable=SC2086
        /usr/bin/time -f "wall %e s (mpirun)" mpirun --allow-run-as-root --oversubscribe -np "$p" \
            "$bin/starplex-mpi" $many --stats > "$tmp/p.json"
        case "$verb" in
            query) cmp -s "$tmp/one.jsonl" "$tmp/p.jsonl" && echo "   file equals the single process: True" \
                       || echo "   file equals the single process: False" ;;
            *) python3 - "$verb" "$tmp/one.json" "$tmp/p.json" <<'PY'
import json, sys
verb = sys.argv[1]
a, b = (json.load(open(x)) for x in sys.argv[2:])
for v in (a, b):
    v.pop("timings", None)
if verb == "simplify":
    print("   single: cells", a["cells"], "vertices", a["vertices"], "| ranks: cells", b["cells"],
          "vertices", b["vertices"], "rounds", b["rounds"], "time_s", round(b["time_s"], 2),
          "(single", round(a["time_s"], 2), ")")
elif verb == "homology":
    print("   Betti numbers equal the single process:", a["betti_z2"] == b["betti_z2"], b["betti_z2"])
else:
    print("   output equals the single process:", a == b)
PY
            ;;
        esac
    done
done
rm -rf "$tmp"
