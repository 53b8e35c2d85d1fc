"""Shared fixtures: the small datasets with their oracles, and the `starplex` binary.

Datasets are found as the Rust tests find them: `$STARPLEX_SHARED/datasets` (else `shared/datasets`
beside the checkout or an ancestor) for the oracles, `.spx` files there and in
`$STARPLEX_DATA/small/*/`. Without them the dataset tests skip, except under `CI=true`.
"""
import json
import os
import pathlib
import shutil

import pytest

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[2]


def data_required():
    return os.environ.get("CI") == "true"


def datasets_dir():
    s = os.environ.get("STARPLEX_SHARED")
    if s:
        return pathlib.Path(s) / "datasets"
    for a in [HERE, *HERE.parents]:
        d = a / "shared" / "datasets"
        if (d / "oracle").is_dir():
            return d
    return REPO.parent / "shared" / "datasets"


def small_datasets():
    """[(name, path of the .spx, oracle dict)] sorted by name."""
    found = {}
    dirs = [datasets_dir() / "small"]
    data = os.environ.get("STARPLEX_DATA")
    if data:
        small = pathlib.Path(data) / "small"
        if small.is_dir():
            dirs += sorted(p for p in small.iterdir() if p.is_dir())
    for d in dirs:
        if d.is_dir():
            for p in sorted(d.glob("*.spx")):
                found.setdefault(p.stem, p)
    out = []
    for name, p in sorted(found.items()):
        o = datasets_dir() / "oracle" / f"{name}.json"
        if o.is_file():
            out.append((name, p, json.loads(o.read_text())))
    return out


SMALL = small_datasets()


def need_data():
    if not SMALL:
        if data_required():
            pytest.fail("CI=true but no small dataset was found (set STARPLEX_SHARED / STARPLEX_DATA)")
        pytest.skip("SKIPPED: no small datasets (set STARPLEX_SHARED / STARPLEX_DATA)")


def starplex_bin():
    """The command line: $STARPLEX_BIN, else the newer of target/{release,debug}/starplex (an
    old release build must not answer for new code), else PATH."""
    b = os.environ.get("STARPLEX_BIN")
    if b:
        return b
    built = [REPO / "target" / prof / "starplex" for prof in ("release", "debug")]
    built = [p for p in built if p.is_file()]
    if built:
        return str(max(built, key=lambda p: p.stat().st_mtime))
    return shutil.which("starplex")


@pytest.fixture(scope="session")
def cli():
    b = starplex_bin()
    if b is None:
        if data_required():
            pytest.fail("CI=true but no starplex binary (run cargo build first or set STARPLEX_BIN)")
        pytest.skip("SKIPPED: no starplex binary (cargo build, or set STARPLEX_BIN)")
    return b
