"""Arrays shared with NumPy without a copy: which inputs are shared, that the views out are
read-only for good, and the memory it saves (resident anonymous memory of a child process)."""
import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import starplex


def grid(n):
    """An n x n grid of squares, two triangles each: float64 points, uint32 triangles."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    pts = np.stack([i.ravel(), j.ravel(), np.zeros(i.size)], axis=1).astype(np.float64)
    v = (np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]).ravel()
    a, b, c, d = v, v + 1, v + n + 1, v + n + 2
    tris = np.concatenate([np.stack([a, b, d], 1), np.stack([a, d, c], 1)]).astype(np.uint32)
    return pts, tris


def mapped(tmp_path, name, a):
    np.save(tmp_path / name, a)
    return np.load(tmp_path / name, mmap_mode="r")


def test_read_only_memory_maps_are_shared(tmp_path):
    pts, tris = grid(6)
    mp, mt = mapped(tmp_path, "p.npy", pts), mapped(tmp_path, "t.npy", tris)
    c = starplex.Complex(mp, mt)
    assert np.shares_memory(c.points, mp) and np.shares_memory(c.cells, mt)
    assert (c.n_vertices, c.n_cells) == (49, 72)
    assert c.info()["euler_characteristic"] == 1
    # the answers are those of the copied complex
    d = starplex.Complex(pts, tris.astype(np.int64))
    assert np.array_equal(c.vt()[1], d.vt()[1])
    assert starplex.IaStar(c).vv(5)[1].tolist() == starplex.IaStar(d).vv(5)[1].tolist()
    # a slice of the map is shared as well (its own bytes, C-contiguous)
    e = starplex.Complex(mp, mt[:10])
    assert np.shares_memory(e.cells, mt) and e.n_cells == 10


def test_memory_anyone_can_write_is_copied(tmp_path):
    pts, tris = grid(3)
    c = starplex.Complex(pts, tris)  # writeable arrays
    assert not np.shares_memory(c.points, pts) and not np.shares_memory(c.cells, tris)
    before = c.points.copy()
    pts[0, 0] = 99.0
    assert np.array_equal(c.points, before)  # the complex kept its own copy
    # read-only, but the owner could be made writeable again: copied
    owner = tris.copy()
    owner.flags.writeable = False
    assert not np.shares_memory(starplex.Complex(pts, owner).cells, owner)
    # a read-only view of a writeable array: copied
    view = tris.view()
    view.flags.writeable = False
    assert not np.shares_memory(starplex.Complex(pts, view).cells, tris)
    # a map opened for copy-on-write ("c") or not C-contiguous, or of another dtype: copied
    np.save(tmp_path / "t.npy", tris)
    cow = np.load(tmp_path / "t.npy", mmap_mode="c")
    assert not np.shares_memory(starplex.Complex(pts, cow).cells, cow)
    ro = mapped(tmp_path, "t2.npy", np.asfortranarray(tris))
    assert not ro.flags.c_contiguous
    assert not np.shares_memory(starplex.Complex(pts, ro).cells, ro)
    wide = mapped(tmp_path, "t3.npy", tris.astype(np.int64))
    assert starplex.Complex(pts, wide).cells.dtype == np.uint32


def test_views_out_are_read_only_for_good():
    pts, tris = grid(2)
    c = starplex.Complex(pts, tris)
    for a in [c.points, c.cells, c.cell_blocks[0][1]]:
        assert not a.flags.writeable and not a.flags.owndata
        with pytest.raises(ValueError):
            a.flags.writeable = True
        with pytest.raises(ValueError):
            a[0, 0] = 1
    p = c.points
    del c  # the view keeps the complex's memory alive
    assert p.shape == (9, 3) and p[8].tolist() == [2.0, 2.0, 0.0]


def test_a_complex_of_another_complexs_views_shares_them():
    pts, tris = grid(2)
    c = starplex.Complex(pts, tris)
    d = starplex.Complex(c.points, c.cells)
    assert np.shares_memory(d.points, c.points) and np.shares_memory(d.cells, c.cells)
    # out-of-range ids in a shared array are refused as in a copied one
    bad = np.frombuffer(np.array([[0, 1, 9]], dtype=np.uint32).tobytes(), dtype=np.uint32)
    with pytest.raises(ValueError, match="9"):
        starplex.Complex(pts, bad.reshape(1, 3))
    with pytest.raises(ValueError, match="not a valid id"):
        big = np.frombuffer(np.array([[0, 1, 2**32 - 1]], dtype=np.uint32).tobytes(), np.uint32)
        starplex.Complex(pts, big.reshape(1, 3))


CHILD = textwrap.dedent(
    """
    import json, sys, numpy as np, starplex
    def anon():
        for line in open("/proc/self/status"):
            if line.startswith("RssAnon:"):
                return int(line.split()[1]) * 1024
    p = np.load(sys.argv[1], mmap_mode="r")
    t = np.load(sys.argv[2], mmap_mode="r")
    if sys.argv[3] == "copy":
        p, t = np.array(p), np.array(t)   # ordinary writeable arrays
    base = anon()
    c = starplex.Complex(p, t)
    pts, cells = c.points, c.cells
    print(json.dumps({"grew": anon() - base, "n": c.n_cells}))
    """
)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/status")
def test_sharing_saves_the_arrays_memory(tmp_path):
    pts, tris = grid(500)  # 251,001 points, 500,000 triangles: 12 MB of arrays
    np.save(tmp_path / "p.npy", pts)
    np.save(tmp_path / "t.npy", tris)
    size = pts.nbytes + tris.nbytes
    grew = {}
    for mode in ["share", "copy"]:
        out = subprocess.run(
            [sys.executable, "-c", CHILD, str(tmp_path / "p.npy"), str(tmp_path / "t.npy"), mode],
            capture_output=True, text=True, check=True,
        )
        r = json.loads(out.stdout)
        assert r["n"] == 500_000
        grew[mode] = r["grew"]
    # copied: the complex holds its own copy of both arrays; shared: neither
    assert grew["copy"] >= 0.9 * size, (grew, size)
    assert grew["share"] <= 0.25 * size, (grew, size)
