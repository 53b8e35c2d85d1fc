#!/usr/bin/env bash
# Runs every cargo-fuzz target of fuzz/ for N seconds each (default 60), one after the other.
#   scripts/fuzz.sh [SECONDS] [TARGET...]
# Needs cargo-fuzz (`cargo install cargo-fuzz`); the nightly-only flags are enabled on a stable
# toolchain with RUSTC_BOOTSTRAP=1. Corpora grow in fuzz/corpus/<target> (git-ignored), seeded
# from fuzz/seeds/<target>; crashes land in fuzz/artifacts/<target>. Exits non-zero on a crash.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
secs=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(spx off stellar_ref medit vtk gmsh obj ply stl spb surface vtu gzip tree)
fi
export RUSTC_BOOTSTRAP=1
status=0
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t"
    echo "== fuzzing $t for ${secs}s"
    if ! cargo fuzz run "$t" "corpus/$t" "seeds/$t" -- \
        -max_total_time="$secs" -max_len=4096 -rss_limit_mb=2048 -timeout=10 -print_final_stats=1; then
        echo "!! $t: crash, timeout or out-of-memory (see fuzz/artifacts/$t)"
        status=1
    fi
done
exit $status
