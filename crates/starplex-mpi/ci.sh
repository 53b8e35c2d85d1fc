#!/bin/sh
# The MPI checks of starplex-mpi: installs OpenMPI and what rsmpi's build needs (Debian packages,
# only when missing and only as root), builds the starplex CLI and starplex-mpi, and runs the
# mpirun tests with 1, 2, 3 and 4 ranks (oversubscribed) on the small datasets.
#   crates/starplex-mpi/ci.sh            (from the repository root or anywhere) everything
#   crates/starplex-mpi/ci.sh setup      only the packages (.ci/run: before one clippy of the workspace)
#   crates/starplex-mpi/ci.sh test       everything but clippy (the packages must be there)
# Environment: STARPLEX_DATA (datasets), STARPLEX_MPI_RANKS (default 1,2,3,4), CI=true makes
# missing datasets or mpirun a failure instead of a skip.
set -eu
cd "$(dirname "$0")/../.."
PHASE=${1:-all}
need=""
command -v mpirun >/dev/null 2>&1 || need="$need openmpi-bin"
dpkg -s libopenmpi-dev >/dev/null 2>&1 || need="$need libopenmpi-dev"
dpkg -s libclang-dev >/dev/null 2>&1 || need="$need libclang-dev"
if [ -n "$need" ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "starplex-mpi: installing$need"
        DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $need \
            || { apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $need; }
    else
        echo "starplex-mpi: missing Debian packages:$need (install them as root)" >&2
        exit 1
    fi
fi
[ "$PHASE" = setup ] && exit 0
# mpirun as root on a machine with fewer cores than ranks
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "$PHASE" != test ]; then
    cargo clippy -p starplex-mpi --all-targets -- -D warnings
fi
# the `starplex` binary the tests compare with, built as the README's `cargo test` builds it
# (nothing to do after .ci/run's `cargo test`; `-p starplex-cli` alone would rebuild the CLI and
# its tests, because the selection changes a dependency's features)
cargo test --no-run
cargo test -p starplex-mpi -- --test-threads 1
