#!/usr/bin/env bash
# CI for the Python package: a venv made here (numpy, pytest, maturin), clippy on the binding,
# one build of the extension as a wheel, installed with pip (the README's install command), pytest.
#   crates/starplex-py/ci.sh          everything
#   crates/starplex-py/ci.sh setup    only the venv (.ci/run: before one clippy of the workspace)
#   crates/starplex-py/ci.sh test     everything but clippy
# Runs from anywhere; uses $STARPLEX_VENV (default target/ci-venv, git-ignored) and python3.
set -euo pipefail
cd "$(dirname "$0")/../.."
PHASE=${1:-all}
VENV=${STARPLEX_VENV:-target/ci-venv}
if [ ! -x "$VENV/bin/python" ]; then
    if ! python3 -m venv "$VENV"; then
        # a bare Debian/Ubuntu has python3 without its venv module: install it when we can
        rm -rf "$VENV"
        if command -v apt-get >/dev/null && [ "$(id -u)" = 0 ]; then
            apt-get update -q && apt-get install -y -q python3-venv
        fi
        python3 -m venv "$VENV"
    fi
fi
export PATH="$PWD/$VENV/bin:$PATH"   # maturin's build backend calls `maturin` by name
export PYO3_PYTHON="$PWD/$VENV/bin/python"
python -m pip install -q numpy pytest "maturin>=1.9,<2"   # quick when they are there
[ "$PHASE" = setup ] && exit 0
if [ "$PHASE" != test ]; then
    cargo clippy -p starplex-py --all-targets -- -D warnings
fi
# the dev profile (its dependencies at opt-level 2, shared with `cargo test`): a release build
# of the extension took ~5 min of CI; `pip install` without the variable builds in release
export MATURIN_PEP517_ARGS="${MATURIN_PEP517_ARGS:---profile dev}"
# a wheel for this machine's CPython, checked against the interpreter's own tags
WHEELS=target/ci-wheels
rm -rf "$WHEELS"
python -m pip wheel -q --no-deps --no-build-isolation -w "$WHEELS" ./crates/starplex-py
python - "$WHEELS" <<'PY'
import pathlib, sys
from pip._vendor.packaging.tags import sys_tags
from pip._vendor.packaging.utils import parse_wheel_filename
wheels = sorted(pathlib.Path(sys.argv[1]).glob("starplex-*.whl"))
assert len(wheels) == 1, f"expected one starplex wheel, got {wheels}"
name, version, _, tags = parse_wheel_filename(wheels[0].name)
ours = set(sys_tags())
assert tags & ours, f"{wheels[0].name} does not install on this Python ({next(iter(ours))} ...)"
print(f"starplex-py: built {wheels[0].name} ({wheels[0].stat().st_size / 1e6:.1f} MB)")
PY
# the README's install command (the same build, cached)
python -m pip install -q --no-build-isolation ./crates/starplex-py
# the tests compare with the command line built by `cargo test` (target/debug/starplex)
python -m pytest -q crates/starplex-py/tests
