"""A seeded random loop fuzzing the array constructor against a brute-force model."""
import numpy as np
import pytest

import starplex

SEED = 20261202


def expected_error(n_points, cells):
    """What the constructor must say about these cells, by brute force (None: valid)."""
    if cells.size and cells.min() < 0:
        return ["not a valid id"]
    for row in cells:  # cells are checked in id order; within one, either problem may be named
        bad = []
        if row.max() >= n_points:
            bad.append("out of range")
        if len(set(row.tolist())) != len(row):
            bad.append("more than once")
        if bad:
            return bad
    keys = [frozenset(r.tolist()) for r in cells]
    if len(set(keys)) != len(keys):
        return ["duplicate", "face"]
    return None


def test_random_arrays():
    rng = np.random.default_rng(SEED)
    made = refused = 0
    for it in range(400):
        n = int(rng.integers(1, 12))
        d = int(rng.integers(1, 4))
        k = int(rng.integers(1, 5))
        m = int(rng.integers(0, 8))
        pts = rng.normal(size=(n, d))
        cells = rng.integers(-1 if it % 7 == 0 else 0, n + (it % 5 == 0), size=(m, k))
        dtype = [np.int8, np.int16, np.int32, np.int64, np.uint16][it % 5]
        if dtype is np.uint16:
            cells = np.abs(cells)
        cells = cells.astype(dtype)
        if it % 3 == 0:  # non-contiguous views
            cells = np.repeat(cells, 2, axis=1)[:, ::2]
            pts = np.asfortranarray(pts)
        want = expected_error(n, cells.astype(np.int64))
        try:
            c = starplex.Complex(pts, cells)
        except ValueError as e:
            refused += 1
            msg = str(e)
            if want is None:
                # a k-subset of another cell ("is a face of") is the one check the model skips
                assert "face" in msg, (it, msg)
            else:
                assert any(w in msg for w in want), (it, want, msg)
            continue
        made += 1
        assert want is None, (it, want)
        assert c.n_vertices == n and c.n_cells == m
        if m:
            assert np.array_equal(c.cells, cells.astype(np.uint32))
        assert np.array_equal(c.points, pts)
        if m and k <= 4:
            s = starplex.IaStar(c)
            off, vt = s.vt()
            # VT is the transpose of the cells
            got = {(v, int(t)) for v in range(n) for t in vt[off[v]:off[v + 1]]}
            assert got == {(int(v), t) for t, row in enumerate(c.cells) for v in row}, it
    assert made > 100 and refused > 50, (made, refused)


@pytest.mark.parametrize("seed", range(3))
def test_random_ids(seed):
    rng = np.random.default_rng(SEED + seed)
    c = starplex.Complex(rng.normal(size=(30, 3)), rng.permutation(30)[:24].reshape(6, 4))
    s = starplex.SimplexTree(c)
    for _ in range(100):
        ids = rng.integers(-3, 34, size=int(rng.integers(0, 6)))
        ok = bool(np.all((ids >= 0) & (ids < 30)))
        try:
            off, vals = s.vv(ids)
        except ValueError:
            assert not ok
            continue
        assert ok and len(off) == len(ids) + 1
