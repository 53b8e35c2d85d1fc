#!/bin/sh
# The MPI checks of starplex-mpi: installs OpenMPI and what rsmpi's build needs (Debian packages,
# only when missing and only as root), builds the starplex CLI and starplex-mpi, and runs the
# mpirun tests with 1, 2, 3 and 4 ranks (oversubscribed) on the small datasets.
#   crates/starplex-mpi/ci.sh            (from the repository root or anywhere)
# Environment: STARPLEX_DATA (datasets), STARPLEX_MPI_RANKS (default 1,2,3,4), CI=true makes
# missing datasets or mpirun a failure instead of a skip.
set -eu
cd "$(dirname "$0")/../.."
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
# mpirun as root on a machine with fewer cores than ranks
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# the test profile, as `cargo test` of the workspace: the library and the `starplex` binary
# built by .ci/run's `cargo test` are reused
cargo clippy -p starplex-mpi --all-targets -- -D warnings
cargo test -p starplex-cli --no-run
cargo test -p starplex-mpi -- --test-threads 1
